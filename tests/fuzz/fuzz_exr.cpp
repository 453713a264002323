// Fuzz target: the OpenEXR reading paths of `render --from`, `convert`, `compare` and `aerial`
// (io/exr_input.hpp's header check, then OpenEXR through read_exr_provenance, read_rgb_exr,
// read_spectral_exr, exr_channel_names and read_exr_channels).
//
// The input is a file's bytes, put in an in-memory file (memfd) that the readers open by path.
// skyspec::Error (IoError, InputError) is the expected outcome of a bad file. Any other
// exception, a crash, a sanitizer report, an allocation over libFuzzer's limit (a declared size
// believed) or a hang is a finding.
//
// Built with libFuzzer (-DSKYSPEC_FUZZ=ON, clang) or with replay_main.cpp (CTest fuzz_replay_exr).

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "io/exr_channels.hpp"
#include "io/provenance.hpp"
#include "io/rgb_exr.hpp"
#include "io/spectral_exr.hpp"
#include "skyspec/error.hpp"

namespace {

[[noreturn]] void finding(const std::string& what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_exr: %s\n  %s\n", what.c_str(), detail.c_str());
  std::abort();
}

// One reader on the file: an Error is fine, anything else is a finding.
template <typename Read>
void read(const char* reader, Read&& r) {
  try {
    r();
  } catch (const skyspec::Error&) {
  } catch (const std::exception& e) {
    finding(std::string("unexpected exception from ") + reader, e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const int fd = memfd_create("fuzz.exr", 0);
  if (fd < 0) finding("memfd_create failed", "");
  if (ftruncate(fd, 0) != 0 || pwrite(fd, data, size, 0) != static_cast<ssize_t>(size))
    finding("cannot write the memfd", "");
  const std::string path = "/proc/self/fd/" + std::to_string(fd);
  read("read_exr_provenance", [&] { skyspec::read_exr_provenance(path); });
  read("exr_channel_names", [&] { skyspec::exr_channel_names(path); });
  read("read_rgb_exr", [&] { skyspec::read_rgb_exr(path); });
  read("read_spectral_exr", [&] { skyspec::read_spectral_exr(path); });
  read("read_exr_channels", [&] { skyspec::read_exr_channels(path, {"Z"}); });
  return 0;
}
