// One writer per output name: two runs that write the same <folder>/<name>.* at once would each
// replace the other's files, and could leave the EXR of one beside the PNG of the other.
//
// OutputLock takes an exclusive flock(2) on "<folder>/.<name>.lock" for as long as a run writes
// the outputs of that name; a second run finds it taken and stops with a clear error at once
// (before rendering) rather than waiting. The lock file is removed when the lock is released;
// the usual race of removing a lock file (a second process that opened the old file before it
// was unlinked) is closed by checking, once locked, that the path still names the locked file.
// The kernel releases the lock when a process dies, so a killed run never blocks the next one.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

namespace skyspec {

/// An exclusive flock(2) on a lock file of its own, for as long as the object lives: the file is
/// created if missing (a regular file only, never through a symbolic link), holds the holder's
/// process id, and is removed on release while still locked (the race this closes: above).
class LockFile {
 public:
  /// The lock on `path`, or null when another process holds it (its process id, when it wrote one,
  /// in *holder). IoError when the file cannot be made or is not a regular file.
  static std::unique_ptr<LockFile> try_lock(const std::filesystem::path& path, std::string* holder = nullptr);
  ~LockFile();
  LockFile(const LockFile&) = delete;
  LockFile& operator=(const LockFile&) = delete;

 private:
  LockFile(std::filesystem::path path, int fd) : path_(std::move(path)), fd_(fd) {}
  std::filesystem::path path_;
  int fd_ = -1;
};

class OutputLock {
 public:
  /// Locks the outputs `name` in `folder`; throws InputError naming `setting` (e.g.
  /// "output.name") when another process holds them, IoError when the lock cannot be made.
  OutputLock(const std::filesystem::path& folder, const std::string& name, const std::string& setting);
  /// The same lock, or null when another process holds it (IoError when it cannot be made).
  static std::unique_ptr<OutputLock> try_lock(const std::filesystem::path& folder, const std::string& name);
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  explicit OutputLock(std::unique_ptr<LockFile> lock) : lock_(std::move(lock)) {}
  static std::filesystem::path lock_path(const std::filesystem::path& folder, const std::string& name);
  std::unique_ptr<LockFile> lock_;
};

/// Removes the temporary files ("<file>.tmp-<pid>-<hex>", base/atomic_file.hpp) that processes
/// which no longer run left in `folder` for files whose names start with `prefix` (a run killed
/// with SIGKILL cannot remove its own). Returns how many were removed.
int remove_stale_temporaries(const std::filesystem::path& folder, const std::string& prefix);

}  // namespace skyspec
