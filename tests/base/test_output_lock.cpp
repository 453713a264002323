#include <boost/test/unit_test.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "base/atomic_file.hpp"
#include "base/output_lock.hpp"
#include "scratch_folder.hpp"
#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_output_lock)

using namespace skyspec;
using skyspec::test::ScratchFolder;
namespace fs = std::filesystem;

BOOST_AUTO_TEST_CASE(a_second_writer_of_a_name_is_refused_and_the_lock_file_goes_away) {
  ScratchFolder dir;
  {
    const OutputLock first(dir.path, "sky", "output.name");
    BOOST_TEST(fs::exists(dir.path / ".sky.lock"));
    try {
      const OutputLock second(dir.path, "sky", "output.name");  // another open file description: refused
      BOOST_FAIL("two writers of one name");
    } catch (const InputError& e) {
      BOOST_TEST(std::string(e.what()).find("another skyspec run (process " + std::to_string(::getpid()) + ")") !=
                 std::string::npos);
    }
    BOOST_CHECK_NO_THROW(OutputLock(dir.path, "other", "output.name"));  // other names are free
  }
  BOOST_TEST(dir.entries().empty());
  BOOST_CHECK_NO_THROW(OutputLock(dir.path, "sky", "output.name"));  // free again
}

BOOST_AUTO_TEST_CASE(only_temporaries_of_processes_that_are_gone_are_removed) {
  ScratchFolder dir;
  const std::string mine = "sky_0000.exr.tmp-" + std::to_string(::getpid()) + "-ab12";
  for (const std::string& name :
       {std::string("sky_0000.exr.tmp-999999999-ab12"), mine, std::string("other.exr.tmp-999999999-1"),
        std::string("sky_0001.exr"), std::string("sky_0002.png.tmp-x-1")})
    std::ofstream(dir.path / name) << "x";
  BOOST_TEST(remove_stale_temporaries(dir.path, "sky_") == 1);
  BOOST_TEST(!fs::exists(dir.path / "sky_0000.exr.tmp-999999999-ab12"));
  BOOST_TEST(fs::exists(dir.path / mine));                         // this process still runs
  BOOST_TEST(fs::exists(dir.path / "other.exr.tmp-999999999-1"));  // another prefix
  BOOST_TEST(fs::exists(dir.path / "sky_0002.png.tmp-x-1"));       // not a process id
}

BOOST_AUTO_TEST_CASE(an_output_that_is_an_input_is_refused) {
  ScratchFolder dir;
  std::ofstream(dir.path / "in.exr") << "x";
  fs::create_symlink(dir.path / "in.exr", dir.path / "link.exr");
  const std::vector<NamedInput> inputs = {{"--image", dir.path / "in.exr"}};
  BOOST_CHECK_THROW(refuse_output_replacing_input(dir.path / "in.exr", "--name", inputs), InputError);
  BOOST_CHECK_THROW(refuse_output_replacing_input(dir.path / "sub" / ".." / "in.exr", "--name", inputs), InputError);
  BOOST_CHECK_THROW(refuse_output_replacing_input(dir.path / "link.exr", "--name", inputs), InputError);
  BOOST_CHECK_NO_THROW(refuse_output_replacing_input(dir.path / "out.exr", "--name", inputs));
}

BOOST_AUTO_TEST_SUITE_END()
