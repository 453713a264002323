#include "base/preparation_progress.hpp"

#include <atomic>
#include <cstring>
#include <mutex>

namespace skyspec {
namespace {
std::atomic<long long> g_done{0}, g_planned{0}, g_phase{0};
std::atomic<const char*> g_what{""};
std::mutex g_phase_mutex;  // only a phase change takes it; the counts stay lock-free
}  // namespace

void plan_preparation(long long units, const char* what) noexcept {
  if (std::strcmp(g_what.load(std::memory_order_acquire), what) != 0) {
    const std::lock_guard<std::mutex> lock(g_phase_mutex);
    if (std::strcmp(g_what.load(std::memory_order_acquire), what) != 0) {
      g_done.store(0, std::memory_order_relaxed);
      g_planned.store(0, std::memory_order_relaxed);
      g_what.store(what, std::memory_order_release);
      g_phase.fetch_add(1, std::memory_order_relaxed);
    }
  }
  g_planned.fetch_add(units, std::memory_order_relaxed);
}
void finish_preparation(long long units) noexcept { g_done.fetch_add(units, std::memory_order_relaxed); }

PreparationProgress preparation_progress() noexcept {
  PreparationProgress p;
  p.done = g_done.load(std::memory_order_relaxed);
  p.planned = g_planned.load(std::memory_order_relaxed);
  p.what = g_what.load(std::memory_order_acquire);
  p.phase = g_phase.load(std::memory_order_relaxed);
  return p;
}

void reset_preparation_progress() noexcept {
  const std::lock_guard<std::mutex> lock(g_phase_mutex);
  g_done.store(0, std::memory_order_relaxed);
  g_planned.store(0, std::memory_order_relaxed);
  g_what.store("", std::memory_order_release);
  g_phase.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace skyspec
