// The disk cache's claims (base/disk_cache.hpp): one process computes a cache file, another that
// wants the same file waits for it; a lock that cannot be made gives no claim and never writes
// through a link. flock(2) locks belong to open file descriptions, so two claims of one process
// exclude each other as two processes' do: threads stand in for processes here.
#include <boost/test/unit_test.hpp>

#include <signal.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "base/cancellation.hpp"
#include "base/disk_cache.hpp"
#include "scratch_folder.hpp"
#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_disk_cache)

using namespace skyspec;
using skyspec::test::ScratchFolder;
namespace fs = std::filesystem;

BOOST_AUTO_TEST_CASE(a_second_claim_waits_for_the_first_and_sees_its_file) {
  ScratchFolder dir;
  const fs::path file = dir.path / "orders-0123456789abcdef.bin";
  // Boost.Test's assertions belong to the main thread: the first claim's thread records what it saw.
  std::atomic<bool> first_holds{false}, release{false}, first_held{false}, first_waited{true}, lock_file{false};
  std::atomic<bool> written_before_release{false};
  std::thread first([&] {
    const CacheFileClaim claim(file);
    first_held = claim.held();
    first_waited = claim.waited();
    lock_file = fs::exists(dir.path / "orders-0123456789abcdef.bin.lock");
    first_holds = true;
    while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::ofstream(file) << "tables";  // the computed file, written before the claim ends
    written_before_release = true;
  });
  while (!first_holds) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::thread releaser([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    release = true;
  });
  {
    const CacheFileClaim second(file);  // blocks until the first is released
    BOOST_TEST(second.held());
    BOOST_TEST(second.waited());
    BOOST_TEST(written_before_release.load());
    BOOST_TEST(fs::exists(file));
  }
  first.join();
  releaser.join();
  BOOST_TEST(first_held.load());
  BOOST_TEST(!first_waited.load());
  BOOST_TEST(lock_file.load());
  BOOST_TEST(!fs::exists(dir.path / "orders-0123456789abcdef.bin.lock"));  // removed with the claim
  const CacheFileClaim third(file);
  BOOST_TEST(!third.waited());
}

BOOST_AUTO_TEST_CASE(no_path_no_claim) {
  const CacheFileClaim none{fs::path()};
  BOOST_TEST(!none.held());
  BOOST_TEST(!none.waited());
}

BOOST_AUTO_TEST_CASE(a_link_under_the_locks_name_gives_no_claim_and_is_not_written_through) {
  ScratchFolder dir;
  const fs::path target = dir.path / "elsewhere";
  fs::create_symlink(target, dir.path / "aerosol-0000000000000001.bin.lock");
  const CacheFileClaim claim(dir.path / "aerosol-0000000000000001.bin");
  BOOST_TEST(!claim.held());
  BOOST_TEST(!fs::exists(target));
  BOOST_TEST(fs::is_symlink(dir.path / "aerosol-0000000000000001.bin.lock"));
}

BOOST_AUTO_TEST_CASE(waiting_stops_when_cancelled) {
  struct ClearAfter {  // no other test sees the request, whatever this one does
    ~ClearAfter() { clear_cancellation_request(); }
  } clear;
  ScratchFolder dir;
  const fs::path file = dir.path / "orders-00000000000000ff.bin";
  const CacheFileClaim held(file);
  std::thread canceller([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    request_cancellation(SIGINT);
  });
  BOOST_CHECK_THROW(CacheFileClaim waiting(file), Cancelled);
  canceller.join();
}

BOOST_AUTO_TEST_CASE(eviction_takes_a_files_leftover_lock_with_it) {
  ScratchFolder dir;
  for (const char* name : {"orders-0000000000000001.bin", "orders-0000000000000002.bin"})
    std::ofstream(dir.path / name) << std::string(1000, 'x');
  std::ofstream(dir.path / "orders-0000000000000001.bin.lock");  // a killed process's
  fs::last_write_time(dir.path / "orders-0000000000000001.bin",
                      fs::last_write_time(dir.path / "orders-0000000000000002.bin") - std::chrono::hours(1));
  BOOST_TEST(evict_table_cache(dir.path, 1500, dir.path / "orders-0000000000000002.bin") == 1000u);
  BOOST_TEST(!fs::exists(dir.path / "orders-0000000000000001.bin"));
  BOOST_TEST(!fs::exists(dir.path / "orders-0000000000000001.bin.lock"));
  BOOST_TEST(fs::exists(dir.path / "orders-0000000000000002.bin"));
}

BOOST_AUTO_TEST_SUITE_END()
