#pragma once
// The C++ view of shaders/shared_constants.h: GLSL's vector types are glm's.
#include "deepgi/settings.hpp"

#include <glm/glm.hpp>

#include <cstddef>

namespace deepgi::shader_shared {
using mat4 = glm::mat4;
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
#include "shared_constants.h"
}  // namespace deepgi::shader_shared

namespace deepgi::shader_shared {
// std140 offsets of the block as GLSL lays it out; a member added, removed or
// reordered on one side without the other stops the build.
static_assert(offsetof(FrameConstants, camera_ray_scale) == 5 * 64);
static_assert(offsetof(FrameConstants, internal_size) == 5 * 64 + 6 * 16);
static_assert(offsetof(FrameConstants, min_separation) == 5 * 64 + 7 * 16);
static_assert(offsetof(FrameConstants, depth_view_range) == 5 * 64 + 7 * 16 + 12);
static_assert(offsetof(FrameConstants, guard_band) == 5 * 64 + 8 * 16);
static_assert(offsetof(FrameConstants, generator) == 5 * 64 + 8 * 16 + 12);
static_assert(offsetof(FrameConstants, light_kind) == 5 * 64 + 9 * 16);
static_assert(offsetof(FrameConstants, temporal_angle) == 5 * 64 + 9 * 16 + 12);
static_assert(sizeof(FrameConstants) == 5 * 64 + 10 * 16,
              "FrameConstants must keep the std140 layout of shared_constants.h");
}  // namespace deepgi::shader_shared
