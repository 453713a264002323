// A fresh, empty folder for one test, removed when the test ends.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <random>
#include <string>
#include <system_error>
#include <vector>

namespace skyspec::test {

struct ScratchFolder {
  std::filesystem::path path;
  explicit ScratchFolder(const std::string& label = "test") {
    std::random_device random;
    path = std::filesystem::temp_directory_path() /
           ("skyspec-" + label + "-" + std::to_string(::getpid()) + "-" + std::to_string(random()));
    std::filesystem::create_directories(path);
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  /// Names of the entries in the folder.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(path)) names.push_back(entry.path().filename().string());
    return names;
  }
};

}  // namespace skyspec::test
