// OpenEXR output streams of skyspec's writers (OpenEXR encodes into an Imf::OStream):
//   StdioOStream       a file through checked stdio calls, with writeback while writing
//   DiscardingOStream  nothing but the length (timing an encoding without touching the disk)
//   MemoryOStream      bytes in memory (a file encoded first, written afterwards; attribute values)
#pragma once

#include <ImfIO.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <future>
#include <memory>
#include <vector>

namespace skyspec {

/// Output through stdio so that every write error (disk full, ...) is seen: OpenEXR's own file
/// stream can lose errors that happen when the file is closed. Throws IoError naming the file.
class StdioOStream : public Imf::OStream {
 public:
  explicit StdioOStream(const std::filesystem::path& path);
  ~StdioOStream() override;
  void write(const char c[], int n) override;
  uint64_t tellp() override;
  void seekp(uint64_t position) override;
  /// Hands what has been written so far to the kernel and has a helper thread flush it to the
  /// disk (fdatasync) while the caller goes on with the next rows. The fsync when the file is
  /// committed then finds little left to write; asynchronous writeback hints (sync_file_range)
  /// alone do not achieve that, because a disk's cache flush waits for all the data since the
  /// last flush (docs/performance.md has the measurement). The helper only waits for
  /// the disk (no CPU time), so a one-thread render still computes on one core. While the
  /// previous flush runs, none is started (small fast bands would otherwise wait for the disk):
  /// the next one, or the commit's fsync, takes these rows. A flush error is reported by the next
  /// call of this or close().
  void start_writeback();
  /// Flush and close; throws IoError if this or any earlier write failed.
  void close();

 private:
  void wait_for_flush();
  [[noreturn]] void fail(const char* what);
  static constexpr size_t kBufferBytes = size_t{1} << 20;
  std::filesystem::path path_;
  std::unique_ptr<char[]> buffer_;  // stdio's buffer, freed after the destructor's fclose
  FILE* file_ = nullptr;
  bool failed_ = false;
  std::future<int> flushing_;  // start_writeback()'s fdatasync: 0 or its errno
};

/// A stream that keeps nothing but its position and length: OpenEXR encodes into it as into a
/// file (render_budget.cpp times writing with it, without touching the disk).
class DiscardingOStream : public Imf::OStream {
 public:
  DiscardingOStream() : Imf::OStream("(discarded)") {}
  void write(const char[], int n) override;
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t position) override { position_ = position; }
  uint64_t length() const { return length_; }

 private:
  uint64_t position_ = 0, length_ = 0;
};

/// Bytes in memory: a file encoded first and written with checked stdio calls afterwards (the RGB
/// EXRs), or an attribute's value to compare (Imf::Attribute::writeValueTo).
class MemoryOStream : public Imf::OStream {
 public:
  MemoryOStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override;
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t position) override { position_ = static_cast<size_t>(position); }
  const std::vector<char>& bytes() const { return bytes_; }

 private:
  std::vector<char> bytes_;
  size_t position_ = 0;
};

}  // namespace skyspec
