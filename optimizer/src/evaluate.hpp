#pragma once

#include <cstdint>

#include "spiral/optimizer.hpp"

namespace spiral::detail {

// K for (n, tau), or some value above `bound` as soon as K is known to exceed
// it. Writes one worst sector when asked (only meaningful if K <= bound).
std::int64_t evaluate(int n, int tau, std::int64_t bound, Sector* worst_sector);

}  // namespace spiral::detail
