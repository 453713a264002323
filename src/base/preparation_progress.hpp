// The counting side of skyspec/preparation_progress.hpp: a builder plans its work before it starts
// and adds what it finishes as it goes (from any thread; lock-free).
#pragma once

#include "skyspec/preparation_progress.hpp"

namespace skyspec {

void plan_preparation(long long units) noexcept;
void finish_preparation(long long units) noexcept;

}  // namespace skyspec
