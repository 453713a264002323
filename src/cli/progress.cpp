#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

#include "interrupt.hpp"
#include "skyspec/preparation_progress.hpp"

namespace skyspec::cli {

namespace {
constexpr int kBarWidth = 30;

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

// "[#####.....]  40%  ETA 12.0s": a fraction done, and the seconds left (negative: unknown yet) or,
// once done, the seconds it took.
std::string bar_text(double fraction, double seconds_left, double elapsed) {
  const int filled = static_cast<int>(fraction * kBarWidth);
  std::string bar(static_cast<size_t>(filled), '#');
  bar.append(static_cast<size_t>(kBarWidth - filled), '.');
  const std::string eta = fraction < 1.0 ? (seconds_left >= 0.0 ? "ETA " + format_seconds(seconds_left) : std::string())
                                         : "elapsed " + format_seconds(elapsed);
  char pct[16];
  std::snprintf(pct, sizeof pct, "%3d%%", static_cast<int>(fraction * 100));
  return "[" + bar + "] " + pct + "  " + eta;
}
}  // namespace

ProgressBar::ProgressBar(std::string label, bool quiet)
    : label_(std::move(label)), active_(!quiet && isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() {
  stop_watching();
  if (active_ && !finished_ && drawn_) std::fputs("\n", stderr);
}

void ProgressBar::draw(const std::string& text) {  // with mutex_ held
  std::string line = label_ + " " + text;
  const size_t length = line.size();
  if (length < drawn_length_) line.append(drawn_length_ - length, ' ');  // over a longer line drawn before
  std::fprintf(stderr, "\r%s   ", line.c_str());
  std::fflush(stderr);
  drawn_ = true;
  drawn_length_ = length;
}

void ProgressBar::watch_preparation() {
  if (!active_ || watcher_.joinable()) return;
  reset_preparation_progress();
  watcher_ = std::thread([this] {
    std::unique_lock<std::mutex> lock(mutex_);
    auto first_build = std::chrono::steady_clock::time_point{};
    long long phase = -1;
    while (!stop_ && !updated_) {
      wake_.wait_for(lock, std::chrono::milliseconds(250));
      if (stop_ || updated_) break;
      const auto now = std::chrono::steady_clock::now();
      const PreparationProgress p = preparation_progress();
      if (p.planned > 0) {
        if (p.phase != phase) first_build = now, phase = p.phase;  // each phase's own ETA
        const double f = p.fraction(), elapsed = std::chrono::duration<double>(now - first_build).count();
        draw(std::string(p.what) + " " + bar_text(f, f > 0.0 ? elapsed / f - elapsed : -1.0, elapsed));
      } else if (now - start_ > std::chrono::seconds(1)) {
        draw("preparing, " + format_seconds(std::chrono::duration<double>(now - start_).count()));
      }
    }
  });
}

void ProgressBar::stop_watching() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (watcher_.joinable()) watcher_.join();
}

void ProgressBar::update(int done, int total) {
  throw_if_interrupted();  // every long loop reports progress: the place to stop on SIGINT/SIGTERM
  if (!active_ || total <= 0) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  if (!updated_) {  // the work's own phase: its rate counts from this first report
    updated_ = true;
    phase_start_ = now;
    phase_first_done_ = done;
    wake_.notify_all();
  }
  if (done < total && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  const double since = std::chrono::duration<double>(now - phase_start_).count();
  const double rate = done > phase_first_done_ ? (done - phase_first_done_) / since : 0.0;
  draw(bar_text(static_cast<double>(done) / total, rate > 0.0 ? (total - done) / rate : -1.0,
                std::chrono::duration<double>(now - start_).count()));
}

void ProgressBar::finish() {
  stop_watching();
  if (active_ && !finished_ && drawn_) {
    if (!updated_)  // a preparation alone (no work reported after it): it is over
      draw(bar_text(1.0, 0.0, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count()));
    std::fputs("\n", stderr);
  }
  finished_ = true;
}

}  // namespace skyspec::cli
