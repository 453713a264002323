#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

#include "interrupt.hpp"

namespace skyspec::cli {

ProgressBar::ProgressBar(std::string label, bool quiet)
    : label_(std::move(label)), active_(!quiet && isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() {
  if (active_ && !finished_) std::fputs("\n", stderr);
}

namespace {
std::string format_seconds(double s) {
  char buf[32];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%4.1fs", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%dm%02ds", static_cast<int>(s) / 60, static_cast<int>(s) % 60);
  else
    std::snprintf(buf, sizeof buf, "%dh%02dm", static_cast<int>(s) / 3600, (static_cast<int>(s) / 60) % 60);
  return buf;
}
}  // namespace

void ProgressBar::update(int done, int total) {
  throw_if_interrupted();  // every long loop reports progress: the place to stop on SIGINT/SIGTERM
  if (!active_ || total <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (done < total && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  const double frac = static_cast<double>(done) / total;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const int width = 30;
  const int filled = static_cast<int>(frac * width);
  std::string bar(static_cast<size_t>(filled), '#');
  bar.append(static_cast<size_t>(width - filled), '.');
  std::string eta = done > 0 && done < total ? "ETA " + format_seconds(elapsed / frac - elapsed)
                                             : "elapsed " + format_seconds(elapsed);
  std::fprintf(stderr, "\r%s [%s] %3d%%  %s   ", label_.c_str(), bar.c_str(), static_cast<int>(frac * 100),
               eta.c_str());
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (active_ && !finished_) std::fputs("\n", stderr);
  finished_ = true;
}

}  // namespace skyspec::cli
