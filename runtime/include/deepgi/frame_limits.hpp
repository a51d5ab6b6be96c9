#pragma once
// Limits on the frame a run may ask for, checked before any GL object exists:
// the guard band widens every internal buffer, so a size that passes the
// per-side check could still exceed what GL allows, or the memory there is.
#include "deepgi/renderer.hpp"

#include <cstdint>

namespace deepgi {

// Bytes of GPU memory (system memory under llvmpipe) the frame's render
// targets take: every internal buffer, the viewport-sized ones and the
// shadow map. Follows the formats the passes allocate (passes/*.cpp).
std::uint64_t estimate_frame_bytes(const RenderSettings& settings);

// Throws InputError when the internal size (viewport plus guard band) is
// above limits::max_internal_side per side, or the estimate above `max_bytes`; the
// messages name the option that changes each (--size, --guard-band,
// --max-gpu-memory).
void check_frame_limits(const RenderSettings& settings, std::uint64_t max_bytes);

}  // namespace deepgi
