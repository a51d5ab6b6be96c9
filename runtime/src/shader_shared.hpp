#pragma once
// The C++ view of shaders/shared_constants.h: GLSL's vector types are glm's.
#include <glm/glm.hpp>

namespace deepgi::shader_shared {
using mat4 = glm::mat4;
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
#include "shared_constants.h"
}  // namespace deepgi::shader_shared

static_assert(sizeof(deepgi::shader_shared::FrameConstants) == 5 * 64 + 10 * 16,
              "FrameConstants must keep the std140 layout of shared_constants.h");
