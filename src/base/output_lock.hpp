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

class OutputLock {
 public:
  /// Locks the outputs `name` in `folder`; throws InputError naming `setting` (e.g.
  /// "output.name") when another process holds them, IoError when the lock cannot be made.
  OutputLock(const std::filesystem::path& folder, const std::string& name, const std::string& setting);
  /// The same lock, or null when another process holds it (IoError when it cannot be made).
  static std::unique_ptr<OutputLock> try_lock(const std::filesystem::path& folder, const std::string& name);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  OutputLock() = default;
  /// Takes the lock; false when another process holds it (the holder's process id in `holder`).
  bool acquire(const std::filesystem::path& folder, const std::string& name, std::string& holder);

  std::filesystem::path path_;
  int fd_ = -1;
};

/// Removes the temporary files ("<file>.tmp-<pid>-<hex>", base/atomic_file.hpp) that processes
/// which no longer run left in `folder` for files whose names start with `prefix` (a run killed
/// with SIGKILL cannot remove its own). Returns how many were removed.
int remove_stale_temporaries(const std::filesystem::path& folder, const std::string& prefix);

}  // namespace skyspec
