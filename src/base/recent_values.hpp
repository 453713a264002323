// The values a process built most recently, by a key that names every input they depend on: the
// scattering-order tables, the sun's column tables and the sky-view tables of recent renders, so
// that renders of the same inputs in one process (the viewer's frames, a Python session, a job's
// worker) share them instead of building them again.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace skyspec {

template <typename T>
class RecentValues {
 public:
  /// Keeps the newest value and at most `older` more, those of at most `older_bytes` in all
  /// (bytes_of each); a value of more than older_bytes is not kept at all.
  RecentValues(std::size_t older, std::size_t older_bytes, std::function<std::size_t(const T&)> bytes_of)
      : older_(older), older_bytes_(older_bytes), bytes_of_(std::move(bytes_of)) {}

  /// The value kept under `key`, or null.
  std::shared_ptr<const T> find(const std::string& key) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const Entry& e : entries_)
      if (e.key == key) return e.value;
    return nullptr;
  }

  /// The value kept under `key`, or else build()'s, kept under it. build() runs outside the lock
  /// (it may take long, in parallel): two threads asking at once may both build.
  template <typename Build>
  std::shared_ptr<const T> get(const std::string& key, Build&& build) {
    if (auto found = find(key)) return found;
    std::shared_ptr<const T> value = build();
    keep(key, value);
    return value;
  }

  /// Keeps `value` under `key` as the newest, dropping the oldest beyond the bounds.
  void keep(const std::string& key, std::shared_ptr<const T> value) {
    if (!value || bytes_of_(*value) > older_bytes_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.push_back(Entry{key, std::move(value)});
    std::size_t bytes = 0;
    for (std::size_t i = entries_.size() - 1; i-- > 0;) {  // the older ones, newest first
      bytes += bytes_of_(*entries_[i].value);
      if (entries_.size() - 1 - i > older_ || bytes > older_bytes_) {
        entries_.erase(entries_.begin(), entries_.begin() + static_cast<std::ptrdiff_t>(i) + 1);
        break;
      }
    }
  }

 private:
  struct Entry {
    std::string key;
    std::shared_ptr<const T> value;
  };
  std::size_t older_, older_bytes_;
  std::function<std::size_t(const T&)> bytes_of_;
  mutable std::mutex mutex_;
  std::vector<Entry> entries_;  // oldest first
};

}  // namespace skyspec
