// A progress bar with an ETA on stderr; silent when stderr is not a terminal or when quiet.
//
// Two phases: the preparation (the scattering-order tables being built: watch_preparation() draws
// skyspec/preparation_progress.hpp's counts from a thread of its own, with their own ETA) and the
// work that update() reports (rows, frames, tasks), whose ETA is from its rate since its first report.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace skyspec::cli {

class ProgressBar {
 public:
  ProgressBar(std::string label, bool quiet);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  /// Draws the preparation until the first update(): the tables' share built and its ETA, or the
  /// time spent so far when nothing is being built (tables read from the cache).
  void watch_preparation();
  void update(int done, int total);
  void finish();
  bool active() const { return active_; }

 private:
  void stop_watching();
  void draw(const std::string& text);

  std::string label_;
  bool active_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_, phase_start_{};
  std::chrono::steady_clock::time_point last_draw_{};
  bool drawn_ = false;       // a line is on the terminal (finish() ends it)
  size_t drawn_length_ = 0;  // its length
  bool updated_ = false;     // update() has reported work: the preparation is over
  int phase_first_done_ = 0;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread watcher_;
};

}  // namespace skyspec::cli
