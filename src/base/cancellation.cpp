#include "base/cancellation.hpp"

#include <atomic>
#include <csignal>
#include <string>

namespace skyspec {
namespace {

// Lock-free, so a signal handler may store to it; relaxed order is enough for a flag that is
// polled again and again.
std::atomic<int> g_request{0};
static_assert(std::atomic<int>::is_always_lock_free);

std::string describe(int signal_number) {
  if (signal_number == SIGINT) return "SIGINT";
  if (signal_number == SIGTERM) return "SIGTERM";
  if (signal_number == SIGHUP) return "SIGHUP";
  if (signal_number <= 0) return "a cancellation request";
  return "signal " + std::to_string(signal_number);
}

}  // namespace

Cancelled::Cancelled(int signal_number)
    : Error("interrupted by " + describe(signal_number) + "; the unfinished output files were removed"),
      signal_(signal_number > 0 ? signal_number : 0) {}

void request_cancellation(int signal_number) noexcept {
  g_request.store(signal_number != 0 ? signal_number : -1, std::memory_order_relaxed);
}

int cancellation_requested() noexcept { return g_request.load(std::memory_order_relaxed); }

void clear_cancellation_request() noexcept { g_request.store(0, std::memory_order_relaxed); }

void throw_if_cancelled() {
  if (const int s = cancellation_requested()) throw Cancelled(s);
}

}  // namespace skyspec
