#include "io/exr_streams.hpp"

#include <unistd.h>  // fdatasync

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>
#include <utility>

#include "skyspec/error.hpp"

namespace skyspec {

StdioOStream::StdioOStream(const std::filesystem::path& path) : Imf::OStream(path.c_str()), path_(path) {
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) fail("cannot open");
  // OpenEXR writes a line block at a time, pieces of a few kB to MB: stdio's default 4 kB
  // buffer turned a 6 MB file into about 1500 write() calls. One buffer of 1 MiB.
  buffer_.reset(new char[kBufferBytes]);
  if (std::setvbuf(file_, buffer_.get(), _IOFBF, kBufferBytes) != 0) buffer_.reset();
}

StdioOStream::~StdioOStream() {
  if (flushing_.valid()) flushing_.wait();  // its errors are another's to report, if any
  if (file_) std::fclose(file_);
}

void StdioOStream::write(const char c[], int n) {
  if (std::fwrite(c, 1, static_cast<size_t>(n), file_) != static_cast<size_t>(n)) fail("cannot write");
}

uint64_t StdioOStream::tellp() {
  const off_t position = ::ftello(file_);
  if (position < 0) fail("cannot tell position in");
  return static_cast<uint64_t>(position);
}

void StdioOStream::seekp(uint64_t position) {
  if (::fseeko(file_, static_cast<off_t>(position), SEEK_SET) != 0) fail("cannot seek in");
}

void StdioOStream::start_writeback() {
  if (std::fflush(file_) != 0) fail("cannot write");
  if (flushing_.valid() && flushing_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
  wait_for_flush();  // done: only its error, if any
  const int fd = ::fileno(file_);
  flushing_ = std::async(std::launch::async, [fd] { return ::fdatasync(fd) == 0 ? 0 : errno; });
}

void StdioOStream::close() {
  wait_for_flush();
  FILE* f = std::exchange(file_, nullptr);
  const bool write_failed = failed_ || std::ferror(f) != 0;
  const bool close_failed = std::fclose(f) != 0;
  if (close_failed) fail("cannot close");
  if (write_failed) {
    failed_ = true;
    throw IoError("cannot write '" + path_.string() + "'");
  }
}

void StdioOStream::wait_for_flush() {
  if (!flushing_.valid()) return;
  if (const int error_number = flushing_.get(); error_number != 0) {
    errno = error_number;
    fail("cannot flush");
  }
}

void StdioOStream::fail(const char* what) {
  failed_ = true;
  throw IoError(std::string(what) + " '" + path_.string() + "': " + std::strerror(errno));
}

void DiscardingOStream::write(const char[], int n) {
  position_ += static_cast<uint64_t>(n);
  length_ = std::max(length_, position_);
}

void MemoryOStream::write(const char c[], int n) {
  const size_t end = position_ + static_cast<size_t>(n);
  if (bytes_.size() < end) bytes_.resize(end);
  std::memcpy(bytes_.data() + position_, c, static_cast<size_t>(n));
  position_ = end;
}

}  // namespace skyspec
