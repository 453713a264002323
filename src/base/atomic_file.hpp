// Files that appear complete or not at all: write to a temporary name in the destination folder,
// flush and fsync, then rename over the final name. If the writer is destroyed without commit(),
// the temporary file is removed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace skyspec {

class AtomicOutputFile {
 public:
  /// Chooses a unique temporary path beside final_path ("<name>.tmp-<random>"). Throws IoError if
  /// the folder does not exist or is not writable (the message names the folder).
  explicit AtomicOutputFile(std::filesystem::path final_path);
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  /// Where the writer must put the bytes.
  const std::filesystem::path& temporary_path() const { return tmp_; }
  const std::filesystem::path& final_path() const { return final_; }
  /// fsync the temporary file, rename it to the final path, fsync the folder. Throws IoError.
  void commit();
  /// Remove the temporary file now (also done by the destructor if not committed).
  void discard() noexcept;

 private:
  std::filesystem::path final_, tmp_;
  bool committed_ = false;
};

/// Writes `bytes` to `path` through an AtomicOutputFile: the file appears complete or not at all.
/// Throws IoError naming the file.
void write_file_atomically(const std::filesystem::path& path, const std::string& bytes);

/// Check up front that a folder exists (or can be created) and is writable; throws InputError
/// naming `setting` (e.g. "--out" or "output.directory") otherwise.
void ensure_writable_directory(const std::filesystem::path& dir, const std::string& setting);

/// An input file of a command and the flag that named it (e.g. {"--image", "beauty.exr"}).
struct NamedInput {
  std::string setting;
  std::filesystem::path path;
};
/// Throws InputError naming `output_setting` when `output` is one of the inputs: the same file
/// (device and inode) when both exist, the same absolute, normalised path (symbolic links
/// resolved) otherwise. An output never replaces a file the command reads.
void refuse_output_replacing_input(const std::filesystem::path& output, const std::string& output_setting,
                                   const std::vector<NamedInput>& inputs);

}  // namespace skyspec
