#version 450 core
// Deep scalable ambient obscurance (docs/design.md, section 5.6): ambient
// visibility of layer 0. Each estimator is an include of its own that
// defines ao_visibility(), chosen when the program is built by
// `#define AO_METHOD DEEPGI_AO_METHOD_*` (sao_pass.cpp builds one program per
// estimator and layer count): ao_published.glsl, ao_solid_angle.glsl and
// ao_spiral_thick.glsl gather the spiral taps of the generated ao_taps.glsl
// (spiral_tap below), ao_march.glsl follows DEEPGI_AO_MARCH_RAYS rays through
// the layers, ao_gtao.glsl and ao_bitmask.glsl march screen-space slices
// (ao_slice.glsl).
//
// Define AO_LAYERS 1 to read layer 0 only (for comparison); the default is 2.
// The blur that follows keys on the depth pyramid and the G-buffer normal, so
// the output is visibility alone: in [0, 1] for the published and march
// methods, signed (at most 1) for the solid-angle method, whose consumers
// clamp it.
#include "frame_constants.glsl"
#include "pass_parameters.h"
#include "gbuffer_encoding.glsl"
#include "math_constants.glsl"
#include "pixel_rotation.glsl"
#include "rotated_grid.glsl"
#include "ao_taps.glsl"

#ifndef AO_LAYERS
#define AO_LAYERS 2
#endif
#ifndef AO_METHOD
#define AO_METHOD DEEPGI_AO_METHOD_MARCH
#endif

// Bindings are this shader's own; sao_pass.cpp binds the same numbers.
layout(binding = 10) uniform sampler2D depth_pyramid;
layout(binding = 0) uniform sampler2DArray gbuffer_normal;
// March, thick spiral and solid angle: both layers' encoded normals (RG, BA)
// at full resolution, copied from the G-buffer by normal_pair.frag, so that a step or
// tap reads both with one fetch.
layout(binding = 11) uniform sampler2D normal_pair;

// sao.thickness, march, thick spiral and bitmask: how deep (m) behind a stored
// surface with no back face behind it (an open mesh: a floor, a wall plane)
// the scene is taken as solid.
layout(std140, binding = DEEPGI_UBO_PASS) uniform SaoBlock {
  SaoParameters sao;
};

layout(location = 0) out float out_visibility;

// Where tap i of the generated spiral lands for this pixel: the depth-pyramid
// texel and level it reads, and the centre of the full-resolution pixel that
// texel's depth came from. False where the tap is off the guard-banded buffer
// (no depth there to test: no occlusion).
bool spiral_tap(int i, ivec2 pixel, mat2 rotation, float radius_pixels, out ivec2 texel, out int level,
                out vec2 tap_centre) {
  ivec2 size = ivec2(frame.internal_size.xy);
  // The clamp keeps the int conversion defined for absurd radii; a tap that
  // far out is off the buffer either way.
  vec2 offset = clamp((rotation * AO_TAP_OFFSETS[i]) * radius_pixels, vec2(-65536.0), vec2(65536.0));
  ivec2 tap = ivec2(floor(vec2(pixel) + 0.5 + offset));
  if (any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, size))) return false;
  // m_i = clamp(floor(log2(h_i / q)), 0, max_mip), in integers: floor(log2(x))
  // of x >= 1 is the highest set bit of floor(x), exact where log2() may round.
  float steps = min(AO_TAP_ALPHAS[i] * radius_pixels / sao.q, 65536.0);
  level = steps < 1.0 ? 0 : min(findMSB(uint(steps)), sao.max_mip);
  // Level sizes follow GL's rule max(1, size >> level). Computed rather than
  // asked of textureSize(): llvmpipe (Mesa 22, LLVM 15) answers textureSize
  // with a lod that varies across the SIMD lanes wrongly, and taps vanish.
  texel = min(tap >> level, max(size >> level, ivec2(1)) - 1);
  // Rebuild the tap where its depth came from: the full-resolution pixel
  // the rotated-grid texel copies (depth_pyramid.comp), not the tap's own
  // pixel. A depth put at the wrong pixel is a point off the surface, which
  // shades open floors seen at a grazing angle.
  tap_centre = vec2(rotated_grid_source_pixel(texel, level, size)) + 0.5;
  return true;
}

// The slice estimators' shared code, here rather than in each of their
// includes: the loader expands every #include once, before the preprocessor
// sees the #if below, so a second include in the next branch would be empty.
#if AO_METHOD == DEEPGI_AO_METHOD_GTAO || AO_METHOD == DEEPGI_AO_METHOD_BITMASK
#include "ao_slice.glsl"
#endif

#if AO_METHOD == DEEPGI_AO_METHOD_PUBLISHED
#include "ao_published.glsl"
#elif AO_METHOD == DEEPGI_AO_METHOD_SOLID_ANGLE
#include "ao_solid_angle.glsl"
#elif AO_METHOD == DEEPGI_AO_METHOD_MARCH
#include "ao_march.glsl"
#elif AO_METHOD == DEEPGI_AO_METHOD_SPIRAL_THICK
#include "ao_spiral_thick.glsl"
#elif AO_METHOD == DEEPGI_AO_METHOD_GTAO
#include "ao_gtao.glsl"
#elif AO_METHOD == DEEPGI_AO_METHOD_BITMASK
#include "ao_bitmask.glsl"
#else
#error AO_METHOD must be one of DEEPGI_AO_METHOD_*
#endif

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(depth_pyramid, pixel, 0).r;
  if (depth <= 0.0) {  // sky: nothing to occlude
    out_visibility = 1.0;
    return;
  }
  float radius = sao.radius;
  float bias = sao.bias;
  float intensity = sao.intensity;
  vec3 position = camera_position_at(vec2(pixel) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
  vec3 normal = decode_normal(texelFetch(gbuffer_normal, ivec3(pixel, 0), 0).xy);

  // Pixels per metre at this depth: P11 * height / 2 / depth, P11 = 1 / ray_scale.y.
  float radius_pixels = radius * (0.5 * frame.internal_size.y) / (frame.camera_ray_scale.y * depth);
  mat2 rotation = pixel_rotation(uvec2(pixel), uint(frame.rotation_seed));
  // This frame's angle of the temporal sequence (frame.cpp), which ao_temporal.frag averages over.
  rotation *= mat2(cos(frame.temporal_angle), sin(frame.temporal_angle), -sin(frame.temporal_angle), cos(frame.temporal_angle));
  // Solid-angle and thick-spiral threshold: the G-buffer samples a surface
  // once per pixel, so a point less than half a pixel footprint at X (metres
  // per pixel at this depth) above the tangent plane cannot be told from X's
  // own surface.
  float footprint_bias = bias + 0.5 * (2.0 * frame.camera_ray_scale.y * depth / frame.internal_size.y);
  out_visibility = ao_visibility(pixel, depth, position, normal, radius, radius_pixels, bias, footprint_bias,
                                 intensity, rotation);
}
