#version 450 core
// Edge-aware separable blur (docs/design.md, section 5.10): one direction per draw,
// Gaussian weights from the generated blur_kernel.glsl, each tap further
// weighted by how well its depth, normal and position agree with the centre's
// surface and by how far it lies from the centre in metres, then renormalised.
//
// The distance term keeps the blur within a fixed world-space reach (a
// fraction of the AO radius, BlurSettings::extent): a kernel of fixed pixel
// radius spans ever more metres on far or grazing surfaces, and there it
// carried the occlusion next to an occluder onto open floor well past where
// the true visibility is 1. The key (layer 0's linear depth and decoded
// normal) comes from bilateral_blur_key.frag, drawn once before both
// directions.
//
// BLUR_SOURCES (1 or 2, set by the pass) signals are filtered with the same
// weights in one draw, one render target each: the weight of a tap (a key
// fetch, a pow, the plane distance) costs several times a source fetch, so the
// frame blurs the AO visibility and the radiosity E together instead of
// computing every weight twice.
//
// The sources may be signed (the solid-angle AV, sao.frag): every weight is
// non-negative, so the blur is a convex average and needs no clamp.
#include "frame_constants.glsl"
#include "pass_parameters.h"
#include "gbuffer_encoding.glsl"
#include "blur_kernel.glsl"

#ifndef BLUR_SOURCES
#define BLUR_SOURCES 1
#endif

// Bindings are this shader's own; bilateral_blur_pass.cpp binds the same numbers.
layout(binding = 12) uniform sampler2D source0;
#if BLUR_SOURCES > 1
layout(binding = 25) uniform sampler2D source1;
#endif
layout(binding = 26) uniform sampler2D key;  // xyz: camera-space normal, w: linear depth

layout(location = 23) uniform ivec2 direction;
layout(std140, binding = DEEPGI_UBO_PASS) uniform BlurBlock {
  BlurParameters blur;
};

layout(location = 0) out vec4 out_value0;
#if BLUR_SOURCES > 1
layout(location = 1) out vec4 out_value1;
#endif

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 centre0 = texelFetch(source0, pixel, 0);
#if BLUR_SOURCES > 1
  vec4 centre1 = texelFetch(source1, pixel, 0);
#endif
  vec4 centre_key = texelFetch(key, pixel, 0);
  float depth = centre_key.w;
  if (depth <= 0.0) {  // sky and background pass through
    out_value0 = centre0;
#if BLUR_SOURCES > 1
    out_value1 = centre1;
#endif
    return;
  }
  // Tolerances scale with depth: a pixel covers more metres further away.
  float depth_tolerance = blur.depth_tolerance * depth;
  float normal_power = blur.normal_power;
  float plane_tolerance = blur.plane_tolerance * depth;
  float world_extent = blur.world_extent;
  // The floor keeps the inverse finite (GLSL leaves x / 0 undefined) when the
  // extent's square underflows.
  float inverse_extent_squared = world_extent > 0.0 ? 1.0 / max(world_extent * world_extent, 1.0e-30) : 0.0;
  // The second source (E) reaches further while a still camera's history is
  // short, back to the shared reach as the frames add up (pass_parameters.h):
  // its noise falls with the frames, and the blur's bias where E curves does
  // not, so a long mean is blurred as little as the AO.
  float inverse_second_extent_squared = inverse_extent_squared;
  if (world_extent > 0.0 && blur.second_extent_start > 0.0) {
    float frames = float(frame.temporal_frame) + 1.0;
    float second_extent = max(world_extent, blur.second_extent_start / frames);
    inverse_second_extent_squared = 1.0 / max(second_extent * second_extent, 1.0e-30);
  }
  vec3 position = camera_position_at(vec2(pixel) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
  vec3 normal = centre_key.xyz;
  ivec2 size = textureSize(source0, 0);

  float total_weight = BLUR_WEIGHTS[BLUR_RADIUS];
  vec4 sum0 = centre0 * total_weight;
#if BLUR_SOURCES > 1
  float total_weight1 = total_weight;
  vec4 sum1 = centre1 * total_weight;
#endif
  for (int k = -BLUR_RADIUS; k <= BLUR_RADIUS; ++k) {
    ivec2 tap = pixel + k * direction;
    if (k == 0 || any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, size))) continue;
    vec4 tap_key = texelFetch(key, tap, 0);
    float tap_depth = tap_key.w;
    if (tap_depth <= 0.0) continue;
    vec3 tap_normal = tap_key.xyz;
    vec3 tap_position = camera_position_at(vec2(tap) + 0.5, tap_depth, frame.internal_size, frame.camera_ray_scale);
    float depth_weight = max(0.0, 1.0 - abs(tap_depth - depth) / depth_tolerance);
    float normal_weight = pow(max(dot(tap_normal, normal), 0.0), normal_power);
    vec3 offset = tap_position - position;
    float plane_weight = max(0.0, 1.0 - abs(dot(offset, normal)) / plane_tolerance);
    float edge_weight = BLUR_WEIGHTS[k + BLUR_RADIUS] * depth_weight * normal_weight * plane_weight;
    float distance_squared = dot(offset, offset);
    float weight = edge_weight * max(0.0, 1.0 - distance_squared * inverse_extent_squared);
    sum0 += texelFetch(source0, tap, 0) * weight;
    total_weight += weight;
#if BLUR_SOURCES > 1
    float weight1 = edge_weight * max(0.0, 1.0 - distance_squared * inverse_second_extent_squared);
    sum1 += texelFetch(source1, tap, 0) * weight1;
    total_weight1 += weight1;
#endif
  }
  out_value0 = sum0 / total_weight;
#if BLUR_SOURCES > 1
  out_value1 = sum1 / total_weight1;
#endif
}
