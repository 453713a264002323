// A progress bar with an ETA on stderr; silent when stderr is not a terminal or when quiet.
#pragma once

#include <chrono>
#include <string>

namespace skyspec::cli {

class ProgressBar {
 public:
  ProgressBar(std::string label, bool quiet);
  ~ProgressBar();
  void update(int done, int total);
  void finish();
  bool active() const { return active_; }

 private:
  std::string label_;
  bool active_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace skyspec::cli
