#pragma once
// CPU evaluation of the deep SAO pass (docs/design.md, section 5.6) and of the
// rotated-grid depth pyramid, written from the formulas rather than from the
// shaders, as the oracle the GPU read-backs are compared with.
// Shared with the shaders rather than derived, so that the comparison can be
// per pixel:
// - the per-pixel rotation hash includes shaders/pixel_rotation_hash.h itself;
//   that hash is checked on its own against values computed from its
//   definition (pixel_rotation_test.cpp);
// - the march repeats sao.frag's choices that no formula fixes: the seed of
//   its per-pixel step offset (0x68e31da4), its golden-angle ray disk, the
//   solid's minimum of two steps, and the 1e-3 z tolerance behind a stored
//   plane; the obscurance's epsilon 1e-4 likewise. A change to any of them
//   in the shader must be made here too; it is not checked independently;
// - the SAO comparison takes the camera ray scale as the renderer computes it
//   (renderer_ray_scale), checked to 1e-6 against the textbook camera's.
#include "deepgi/image_io.hpp"
#include "deepgi/renderer.hpp"

#include <spiral/codegen.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace deepgi::test {

// The per-pixel rotation of pixel_rotation.glsl, in 32-bit unsigned arithmetic;
// seed is the rotation-seed setting (0: the shipped field the references use).
std::uint32_t pixel_rotation_hash(std::uint32_t x, std::uint32_t y, std::uint32_t seed = 0);
float pixel_rotation_angle(std::uint32_t x, std::uint32_t y, std::uint32_t seed = 0);
// The per-pixel salted hashes' mixer (pixel_rotation_hash.h), for the step
// offsets and jitters the shaders derive from the pixel hash.
std::uint32_t avalanche32(std::uint32_t x);

// What the pass reads, as read back from the GPU.
struct SaoInputs {
    std::vector<FloatImage>
        pyramid;                // level m: channel 0 layer-0 depth, 1 layer-1 depth; 0 = no surface
    FloatImage normals;         // layer-0 camera-space normals, 3 channels
    FloatImage normals_layer1;  // layer-1 normals (read by the solid-angle method)
    // The march only: per layer, the linear depth of the nearest back face at
    // or behind the stored surface (0 = none), as the back-face pass wrote it.
    std::vector<FloatImage> back_faces;
    glm::vec2 ray_scale{1.0f};  // (1/P00, 1/P11) of the guard-banded projection
    float near_plane = 0.05f;   // the camera's (m): the march stops in front of it
    // The depth pyramid's MIP selection constant (RenderSettings::depth_pyramid.q).
    float q = 8.0f;
};

// Ambient visibility per pixel (1 channel, the pyramid's level-0 size): in
// [0, 1] for the published and march methods, signed (at most 1) for the
// solid-angle one. The first frame's: the frame sequence at its point 0 (no extra rotation).
// thick_sectors: the thick spiral's azimuth sectors, 0 for the shader's count
// for taps.size() (shaders/ao_thick_sectors.h), at most 8.
FloatImage reference_ambient_visibility(const SaoInputs& inputs,
                                        const std::vector<spiral::codegen::Tap>& taps,
                                        const AoSettings& settings, int thick_sectors = 0);

// Pixel centre (x + 1/2, y + 1/2) at linear depth z, as camera_position_at()
// in gbuffer_encoding.glsl defines camera space: x, y from the NDC of the
// centre of the pyramid's level-0 grid.
glm::vec3 camera_position(float centre_x, float centre_y, float depth, const SaoInputs& inputs);

// Level m + 1 of the pyramid from level m by the rotated-grid rule.
FloatImage reference_pyramid_level(const FloatImage& finer);

// Camera ray scale (1/P00, 1/P11) of the guard-banded projection for these
// settings, from the textbook camera (tests/support/textbook_camera.hpp).
glm::vec2 camera_ray_scale(const Camera& camera, const RenderSettings& settings);

// The same scale as the renderer computes it, from guard_band_projection.
// The per-pixel comparisons of discrete decisions (a tap inside a solid or
// not) use this one: a 1-ulp difference in the scale flips a handful of
// thick-spiral taps. The textbook value is checked against it to 1e-6 in
// sao_test.cpp, so the two describe one camera.
glm::vec2 renderer_ray_scale(const Camera& camera, const RenderSettings& settings);

}  // namespace deepgi::test
