// Atomic file replacement: write "<name>.tmp-<pid>-<random>" beside the destination, fsync it,
// rename(2) it over the destination (atomic within one file system, POSIX), then fsync the folder
// so that the new directory entry itself survives a crash.
#include "base/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <system_error>

#include "skyspec/error.hpp"

namespace skyspec {
namespace fs = std::filesystem;
namespace {

/// "<what> '<path>': <strerror(errno)>".
IoError io_error(const std::string& what, const fs::path& path, int error_number) {
  return IoError(what + " '" + path.string() + "': " + std::strerror(error_number));
}

/// The folder that holds `file` ("." for a bare file name).
fs::path folder_of(const fs::path& file) {
  const fs::path parent = file.parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

/// A name no other writer will pick: the process id plus 64 random bits.
fs::path temporary_name_beside(const fs::path& final_path) {
  static thread_local std::mt19937_64 random_bits{std::random_device{}()};
  std::ostringstream name;
  name << final_path.filename().string() << ".tmp-" << ::getpid() << "-" << std::hex << random_bits();
  return folder_of(final_path) / name.str();
}

/// open(2) + fsync(2) + close(2); `flags` is O_WRONLY for a file, O_RDONLY | O_DIRECTORY for a
/// folder (Linux allows fsync on a read-only descriptor of a folder).
void fsync_path(const fs::path& path, int flags, const char* what) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) throw io_error(std::string("cannot open ") + what, path, errno);
  if (::fsync(fd) != 0) {
    const int error_number = errno;
    ::close(fd);
    throw io_error(std::string("cannot flush ") + what, path, error_number);
  }
  if (::close(fd) != 0) throw io_error(std::string("cannot close ") + what, path, errno);
}

}  // namespace

std::string file_kind(const fs::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return errno == ENOENT ? "missing" : "unreadable";
  if (S_ISREG(st.st_mode)) return "a regular file";
  if (S_ISLNK(st.st_mode)) return "a symbolic link";
  if (S_ISDIR(st.st_mode)) return "a folder";
  if (S_ISCHR(st.st_mode)) return "a character device";
  if (S_ISBLK(st.st_mode)) return "a block device";
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  return "not a regular file";
}

void refuse_to_replace_non_regular(const fs::path& path) {
  const std::string kind = file_kind(path);
  if (kind == "missing" || kind == "a regular file") return;
  throw IoError("refusing to write '" + path.string() + "': it is " + kind +
                "; skyspec creates and replaces only regular files (name a new file or a regular one)");
}

bool is_regular_input(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

AtomicOutputFile::AtomicOutputFile(fs::path final_path) : final_(std::move(final_path)) {
  if (final_.empty() || !final_.has_filename())
    throw IoError("cannot write to '" + final_.string() + "': not a file name");
  refuse_to_replace_non_regular(final_);
  // Reserve the temporary name with O_EXCL so that two writers can never share it; the caller's
  // library then truncates and fills it.
  constexpr int kAttempts = 16;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    const fs::path candidate = temporary_name_beside(final_);
    const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      tmp_ = candidate;
      return;
    }
    if (errno != EEXIST) throw io_error("cannot create a file in folder", folder_of(final_), errno);
  }
  throw io_error("cannot find a free temporary name in folder", folder_of(final_), EEXIST);
}

AtomicOutputFile::~AtomicOutputFile() {
  if (!committed_) discard();
}

void AtomicOutputFile::commit() {
  if (committed_) throw IoError("'" + final_.string() + "' was already committed");
  fsync_path(tmp_, O_WRONLY, "file");
  refuse_to_replace_non_regular(final_);  // again: it may have appeared while the file was written
  if (::rename(tmp_.c_str(), final_.c_str()) != 0)
    throw io_error("cannot rename '" + tmp_.string() + "' to", final_, errno);
  committed_ = true;
  fsync_path(folder_of(final_), O_RDONLY | O_DIRECTORY, "folder");
}

void AtomicOutputFile::discard() noexcept {
  if (committed_ || tmp_.empty()) return;
  ::unlink(tmp_.c_str());  // nothing useful to do if it is already gone
}

void write_file_atomically(const fs::path& path, const std::string& bytes) {
  AtomicOutputFile file(path);
  {
    std::ofstream stream(file.temporary_path(), std::ios::binary);
    stream << bytes;
    stream.flush();
    if (!stream) throw IoError("cannot write " + file.temporary_path().string());
  }
  file.commit();
}

OutputFolderGuard::OutputFolderGuard(fs::path dir, const std::string& setting) : dir_(std::move(dir)) {
  std::error_code ec;
  const bool existed = dir_.empty() || fs::exists(fs::symlink_status(dir_, ec));
  ensure_writable_directory(dir_, setting);
  created_ = !existed;
}

OutputFolderGuard::~OutputFolderGuard() {
  if (!created_) return;
  std::error_code ec;
  fs::remove(dir_, ec);  // only an empty folder is removed; one with files stays as it is
}

void ensure_writable_directory(const fs::path& dir, const std::string& setting) {
  const auto refuse = [&]() {
    return InputError(setting, dir.string(), "a folder that exists or can be created and is writable");
  };
  const fs::path folder = dir.empty() ? fs::path(".") : dir;
  std::error_code error;
  fs::create_directories(folder, error);  // no error if it already exists as a folder
  if (error || !fs::is_directory(folder, error)) throw refuse();
  // W_OK to add entries, X_OK to reach them. (root passes unless the file system is read-only.)
  if (::access(folder.c_str(), W_OK | X_OK) != 0) throw refuse();
}

}  // namespace skyspec

namespace skyspec {

void refuse_output_replacing_input(const fs::path& output, const std::string& output_setting,
                                   const std::vector<NamedInput>& inputs) {
  for (const NamedInput& in : inputs) {
    if (in.path.empty()) continue;
    std::error_code ec;
    bool same = fs::exists(output, ec) && fs::exists(in.path, ec) && fs::equivalent(output, in.path, ec);
    if (!same) {
      const fs::path a = fs::weakly_canonical(fs::absolute(output, ec), ec),
                     b = fs::weakly_canonical(fs::absolute(in.path, ec), ec);
      same = !a.empty() && a == b;
    }
    if (same)
      throw InputError(output_setting, "\"" + output.string() + "\"",
                       "an output that is not one of the inputs (it would replace " + in.setting + " " +
                           in.path.string() + "); choose another --out or --name");
  }
}

}  // namespace skyspec
