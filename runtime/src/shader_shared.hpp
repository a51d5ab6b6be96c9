#pragma once
// The C++ view of shaders/shared_constants.h: GLSL's vector types are glm's.
#include "deepgi/gl_objects.hpp"
#include "deepgi/settings.hpp"

#include <glm/glm.hpp>

#include <cstddef>

namespace deepgi::shader_shared {
using mat4 = glm::mat4;
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
#include "shared_constants.h"
#include "pass_parameters.h"
}  // namespace deepgi::shader_shared

namespace deepgi::shader_shared {
// std140 offsets of the block as GLSL lays it out; a member added, removed or
// reordered on one side without the other stops the build.
static_assert(offsetof(FrameConstants, camera_ray_scale) == 5 * 64);
static_assert(offsetof(FrameConstants, internal_size) == 5 * 64 + 6 * 16);
static_assert(offsetof(FrameConstants, min_separation) == 5 * 64 + 7 * 16);
static_assert(offsetof(FrameConstants, shadow_normal_offset) == 5 * 64 + 7 * 16 + 8);
static_assert(offsetof(FrameConstants, guard_band) == 5 * 64 + 8 * 16);
static_assert(offsetof(FrameConstants, generator) == 5 * 64 + 8 * 16 + 12);
static_assert(offsetof(FrameConstants, light_kind) == 5 * 64 + 9 * 16);
static_assert(offsetof(FrameConstants, temporal_angle) == 5 * 64 + 9 * 16 + 12);
static_assert(offsetof(FrameConstants, temporal_sample) == 5 * 64 + 10 * 16);
static_assert(offsetof(FrameConstants, ao_term) == 5 * 64 + 11 * 16);
static_assert(offsetof(FrameConstants, reflection_term) == 5 * 64 + 11 * 16 + 12);
static_assert(offsetof(FrameConstants, next_view) == 5 * 64 + 12 * 16);
static_assert(offsetof(FrameConstants, next_projection) == 6 * 64 + 12 * 16);
static_assert(sizeof(FrameConstants) == 7 * 64 + 12 * 16,
              "FrameConstants must keep the std140 layout of shared_constants.h");
}  // namespace deepgi::shader_shared

namespace deepgi::shader_shared {
// The passes' own blocks: scalars only, whole 16-byte rows (pass_parameters.h).
static_assert(sizeof(SaoParameters) == 32 && offsetof(SaoParameters, max_mip) == 16);
static_assert(sizeof(RadiosityGatherParameters) == 32 &&
              offsetof(RadiosityGatherParameters, layers) == 16);
static_assert(sizeof(RadiosityPrepareParameters) == 16);
static_assert(sizeof(BlurParameters) == 32);
static_assert(sizeof(AntialiasParameters) == 16);
static_assert(sizeof(ReflectionParameters) == 48 &&
              offsetof(ReflectionParameters, max_level) == 16 &&
              offsetof(ReflectionParameters, edge_fade_pixels) == 32);
}  // namespace deepgi::shader_shared

namespace deepgi {
// A pass's own uniform block: uploaded and bound at DEEPGI_UBO_PASS right
// before the pass draws with it.
template <class Block>
class ParameterBlock {
public:
    ParameterBlock() : buffer_(gl::create_buffer()) {
        glNamedBufferStorage(buffer_.get(), sizeof(Block), nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    void bind(const Block& values) const {
        glNamedBufferSubData(buffer_.get(), 0, sizeof(Block), &values);
        glBindBufferBase(GL_UNIFORM_BUFFER, DEEPGI_UBO_PASS, buffer_.get());
    }

private:
    gl::Buffer buffer_;
};
}  // namespace deepgi
