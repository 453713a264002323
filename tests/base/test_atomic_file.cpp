#include <boost/test/unit_test.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "base/atomic_file.hpp"
#include "io/png_image.hpp"
#include "scratch_folder.hpp"
#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_atomic_file)

using namespace skyspec;
using skyspec::test::ScratchFolder;
namespace fs = std::filesystem;

using skyspec::test::read_all;
using skyspec::test::write_text;

BOOST_AUTO_TEST_CASE(commit_renames_the_temporary_file) {
  ScratchFolder dir;
  const fs::path target = dir.path / "out.txt";
  write_text(target, "old");
  {
    AtomicOutputFile file(target);
    BOOST_TEST(file.final_path() == target);
    BOOST_TEST(file.temporary_path().parent_path() == dir.path);
    BOOST_TEST(file.temporary_path().filename().string().rfind("out.txt.tmp-", 0) == 0u);
    BOOST_TEST(fs::exists(file.temporary_path()));  // the name is reserved at once
    write_text(file.temporary_path(), "new");
    BOOST_TEST(read_all(target) == "old");  // untouched until commit
    file.commit();
    BOOST_TEST(!fs::exists(file.temporary_path()));
    BOOST_CHECK_THROW(file.commit(), IoError);
  }
  BOOST_TEST(read_all(target) == "new");
  BOOST_TEST(dir.entries() == std::vector<std::string>{"out.txt"});
}

BOOST_AUTO_TEST_CASE(two_writers_get_different_temporary_names) {
  ScratchFolder dir;
  AtomicOutputFile a(dir.path / "x"), b(dir.path / "x");
  BOOST_TEST(a.temporary_path() != b.temporary_path());
}

BOOST_AUTO_TEST_CASE(discard_and_destructor_remove_the_temporary_file) {
  ScratchFolder dir;
  {
    AtomicOutputFile file(dir.path / "a.bin");
    write_text(file.temporary_path(), "partial");
    file.discard();
    BOOST_TEST(!fs::exists(file.temporary_path()));
  }
  {
    AtomicOutputFile file(dir.path / "b.bin");
    write_text(file.temporary_path(), "partial");
  }
  BOOST_TEST(dir.entries().empty());
}

BOOST_AUTO_TEST_CASE(missing_folder_is_an_io_error_naming_it) {
  ScratchFolder dir;
  const fs::path missing = dir.path / "no" / "such" / "folder";
  try {
    AtomicOutputFile file(missing / "out.exr");
    BOOST_FAIL("expected IoError");
  } catch (const IoError& e) {
    BOOST_TEST(std::string(e.what()).find(missing.string()) != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(ensure_writable_directory_creates_missing_folders) {
  ScratchFolder dir;
  const fs::path nested = dir.path / "renders" / "today";
  BOOST_CHECK_NO_THROW(ensure_writable_directory(nested, "--out"));
  BOOST_TEST(fs::is_directory(nested));
  BOOST_CHECK_NO_THROW(ensure_writable_directory(nested, "--out"));  // exists already: fine
}

// Tests run as root, for whom permission bits do not stop anything; a folder below a regular
// FILE can be created by nobody, and neither can one below /proc.
BOOST_AUTO_TEST_CASE(unwritable_folder_error_names_the_setting) {
  ScratchFolder dir;
  const fs::path regular_file = dir.path / "plain.txt";
  write_text(regular_file, "not a folder");
  for (const fs::path& impossible : {regular_file / "sub", regular_file, fs::path("/proc/skyspec-test/sub")}) {
    try {
      ensure_writable_directory(impossible, "output.directory");
      BOOST_FAIL("expected InputError for " + impossible.string());
    } catch (const InputError& e) {
      BOOST_TEST(e.setting() == "output.directory");
      BOOST_TEST(e.value() == impossible.string());
      BOOST_TEST(std::string(e.what()).find("output.directory") != std::string::npos);
      BOOST_TEST(e.allowed() == "a folder that exists or can be created and is writable");
    }
  }
}

// write_png_srgb8 is atomic too: a good image leaves exactly one file with a PNG signature and an
// sRGB chunk; a bad value leaves nothing.
BOOST_AUTO_TEST_CASE(png_preview_is_written_atomically) {
  ScratchFolder dir;
  const int width = 4, height = 3;
  std::vector<float> rgb(static_cast<size_t>(width * height * 3));
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<float>(i) / static_cast<float>(rgb.size());
  const fs::path png = dir.path / "preview.png";
  write_png_srgb8(png, width, height, rgb, 1.0);
  BOOST_TEST(dir.entries() == std::vector<std::string>{"preview.png"});
  const std::string bytes = read_all(png);
  BOOST_TEST(bytes.substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8));
  BOOST_TEST(bytes.find("sRGB") != std::string::npos);
  BOOST_TEST(bytes.find("IEND") != std::string::npos);

  rgb[5] = std::nanf("");
  const fs::path bad = dir.path / "bad.png";
  BOOST_CHECK_THROW(write_png_srgb8(bad, width, height, rgb, 1.0), IoError);
  BOOST_CHECK_THROW(write_png_srgb8(bad, width, height, std::vector<float>(5), 1.0), IoError);
  BOOST_TEST(dir.entries() == std::vector<std::string>{"preview.png"});
}

BOOST_AUTO_TEST_SUITE_END()  // test_atomic_file
