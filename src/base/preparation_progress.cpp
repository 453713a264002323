#include "base/preparation_progress.hpp"

#include <atomic>

namespace skyspec {
namespace {
std::atomic<long long> g_done{0}, g_planned{0};
}  // namespace

void plan_preparation(long long units) noexcept { g_planned.fetch_add(units, std::memory_order_relaxed); }
void finish_preparation(long long units) noexcept { g_done.fetch_add(units, std::memory_order_relaxed); }

PreparationProgress preparation_progress() noexcept {
  PreparationProgress p;
  p.done = g_done.load(std::memory_order_relaxed);
  p.planned = g_planned.load(std::memory_order_relaxed);
  return p;
}

void reset_preparation_progress() noexcept {
  g_done.store(0, std::memory_order_relaxed);
  g_planned.store(0, std::memory_order_relaxed);
}

}  // namespace skyspec
