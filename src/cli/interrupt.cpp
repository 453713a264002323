#include "interrupt.hpp"

#include <csignal>
#include <cstring>

namespace skyspec::cli {
namespace {

extern "C" void record_signal(int signal_number) { skyspec::request_cancellation(signal_number); }

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = record_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // a second signal gets the default action
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  // A dropped SSH session or a closed terminal: stop as for SIGTERM, removing the temporaries and
  // the lock (docs/reliability.md, round 3, item 10).
  sigaction(SIGHUP, &action, nullptr);
}

}  // namespace skyspec::cli
