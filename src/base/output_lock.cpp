#include "base/output_lock.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "base/atomic_file.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace fs = std::filesystem;

fs::path OutputLock::lock_path(const fs::path& folder, const std::string& name) {
  return (folder.empty() ? fs::path(".") : folder) / ("." + name + ".lock");
}

OutputLock::OutputLock(const fs::path& folder, const std::string& name, const std::string& setting) {
  std::string holder;
  lock_ = LockFile::try_lock(lock_path(folder, name), &holder);
  if (!lock_)
    throw InputError::refused(setting, "another skyspec run" +
                                           (holder.empty() ? std::string() : " (process " + holder + ")") +
                                           " is writing the outputs named \"" + name + "\" in " + folder.string() +
                                           "; wait for it to finish or choose another --out or --name");
}

std::unique_ptr<OutputLock> OutputLock::try_lock(const fs::path& folder, const std::string& name) {
  std::unique_ptr<LockFile> lock = LockFile::try_lock(lock_path(folder, name));
  if (!lock) return nullptr;
  return std::unique_ptr<OutputLock>(new OutputLock(std::move(lock)));
}

std::unique_ptr<LockFile> LockFile::try_lock(const fs::path& path, std::string* holder) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    // Never through a symbolic link (O_NOFOLLOW: ELOOP), never anything but a regular file: a
    // link planted in the output folder would otherwise have its target truncated.
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
    if (fd < 0 && errno == ELOOP)
      throw IoError("refusing to use the lock file '" + path.string() +
                    "': it is a symbolic link; skyspec creates and replaces only regular files");
    if (fd < 0) throw IoError("cannot create the lock file '" + path.string() + "': " + std::strerror(errno));
    struct stat kind {};
    if (::fstat(fd, &kind) != 0 || !S_ISREG(kind.st_mode)) {
      ::close(fd);
      throw IoError("refusing to use the lock file '" + path.string() + "': it is " + file_kind(path) +
                    ", not a regular file");
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error_number = errno;
      if (error_number == EWOULDBLOCK && holder) std::getline(std::ifstream(path), *holder);
      ::close(fd);
      if (error_number != EWOULDBLOCK)
        throw IoError("cannot lock '" + path.string() + "': " + std::strerror(error_number));
      return nullptr;
    }
    // Locked: but if the holder before us removed the file meanwhile, ours is no longer the file
    // at that path and a third run could lock a new one. Then start again.
    struct stat held {
    }, named{};
    if (::fstat(fd, &held) == 0 && ::stat(path.c_str(), &named) == 0 && held.st_dev == named.st_dev &&
        held.st_ino == named.st_ino) {
      // The process id, for the message of a run that finds the lock taken; not writing it is harmless.
      const std::string pid = std::to_string(::getpid()) + "\n";
      if (::ftruncate(fd, 0) == 0) static_cast<void>(::write(fd, pid.data(), pid.size()) > 0);
      return std::unique_ptr<LockFile>(new LockFile(path, fd));
    }
    ::close(fd);
  }
  throw IoError("cannot lock '" + path.string() + "': it keeps being replaced");
}

LockFile::~LockFile() {
  ::unlink(path_.c_str());  // while still locked: the next holder creates (and locks) a new file
  ::close(fd_);
}

int remove_stale_temporaries(const fs::path& folder, const std::string& prefix) {
  int removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(folder.empty() ? fs::path(".") : folder, ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string file = it->path().filename().string();
    if (file.rfind(prefix, 0) != 0) continue;
    const std::size_t tmp = file.rfind(".tmp-");
    if (tmp == std::string::npos) continue;
    const std::size_t dash = file.find('-', tmp + 5);
    if (dash == std::string::npos) continue;
    char* end_of_pid = nullptr;
    const long pid = std::strtol(file.c_str() + tmp + 5, &end_of_pid, 10);
    if (pid <= 0 || end_of_pid != file.c_str() + dash) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // its writer still runs
    if (std::error_code rm; fs::remove(it->path(), rm)) ++removed;
  }
  return removed;
}

}  // namespace skyspec
