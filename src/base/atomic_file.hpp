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

/// What kind of file system entry `path` is, without following a symbolic link at its end:
/// "missing", "a regular file", "a symbolic link", "a folder", "a character device", "a block
/// device", "a FIFO", "a socket".
std::string file_kind(const std::filesystem::path& path);
/// Throws IoError naming the path and its kind unless it is missing or a regular file: skyspec
/// creates and replaces only regular files, never a symbolic link (nor what it points to), a
/// device such as /dev/null or /dev/stdout, a FIFO or a folder. AtomicOutputFile checks its final
/// path with it before writing and again before the rename.
void refuse_to_replace_non_regular(const std::filesystem::path& path);
/// Whether `path` is a regular file (following links): the only kind skyspec reads as a data file
/// (a FIFO or a device named like one would block the reader or feed it anything).
bool is_regular_input(const std::filesystem::path& path);

/// Writes `bytes` to `path` through an AtomicOutputFile: the file appears complete or not at all.
/// Throws IoError naming the file.
void write_file_atomically(const std::filesystem::path& path, const std::string& bytes);

/// Check up front that a folder exists (or can be created) and is writable; throws InputError
/// naming `setting` (e.g. "--out" or "output.directory") otherwise.
void ensure_writable_directory(const std::filesystem::path& dir, const std::string& setting);

/// A folder that a command is about to create for its outputs: made by ensure_writable_directory,
/// removed again when the guard goes out of scope if this guard's check created it and it is still
/// empty (a refused or failed command leaves no empty output folder behind).
class OutputFolderGuard {
 public:
  /// Checks the folder as ensure_writable_directory does (InputError naming `setting`).
  OutputFolderGuard(std::filesystem::path dir, const std::string& setting);
  ~OutputFolderGuard();
  OutputFolderGuard(const OutputFolderGuard&) = delete;
  OutputFolderGuard& operator=(const OutputFolderGuard&) = delete;

 private:
  std::filesystem::path dir_;
  bool created_ = false;
};

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
