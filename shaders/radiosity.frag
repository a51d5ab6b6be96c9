#version 450 core
// Deep radiosity gather (docs/design.md, section 5.9) for one G-buffer layer (uniform
// `layer`): irradiance E at X from the taps of the generated
// radiosity_taps.glsl, each tap reading both depth layers.
//
// A sample (tap i, layer j) is used when Y lies within the world-space radius,
// X faces it (w.n_X > 0) and it faces X (-w.n_Y > 0), w = (Y - X) / |Y - X|.
// B(Y) is the outgoing radiance radiosity_prepare.comp wrote (direct light,
// last frame's bounce, boost and emissive), n_Y its normal and Y is rebuilt
// from the depth pyramid. Tap i reads MIP level
// m_i = clamp(floor(log2(alpha_i R / q)), 0, max) of all three, as SAO does:
// the rotated-grid texel's depth and normal are one level-0 pixel's, and Y is
// rebuilt at that pixel's centre; its B is by default the mean over that
// pixel's surface within the texel's block (docs/radiosity.md, "Prefiltered
// levels").
//
// DEEPGI_RADIOSITY_METHOD_AREA estimates the reference's one-bounce
// irradiance (reference.hpp)
//   E(X) = int_hemisphere L(y) cos(theta_X) dw
// over the surfaces the G-buffer holds, as sao.frag's solid-angle AO does:
// dw = cos(theta_Y) dA / |v|^2, the patch behind a pixel at linear depth z_Y
// has the area (s z_Y)^2 cos(phi) / cos(view_Y) (s: pixel side at unit
// depth, phi: the pixel's angle off the optical axis, view_Y: between n_Y
// and the direction to the eye), and tap i, at radius alpha_i R (R = k r / (s z_X) pixels,
// uniform in radius), stands for 2 pi alpha_i R^2 / N pixels. So sample (i, j)
// covers the solid angle
//   W_ij = 2 pi / N * w_ij,
//   w_ij = alpha_i k^2 (z_Y / z_X)^2 cos(phi) cos(theta_Y) r^2 / (|v|^2 cos(view_Y))
// and
//   E(X) ~= 2 pi / N * sum over used samples of min(B(Y) cos(theta_X) w_ij, clamp)
//   c(X)  = min(1, 2 / N * sum over used samples of cos(theta_X) w_ij)
// k widens the disk from the projection of r at X's depth towards the
// projection of the whole ball of radius r about X (exact on the optical
// axis), since the ball's points nearer the camera than X project further
// from X than r does at z_X: without it the floor before a wall facing the
// camera never reaches the wall's gather. The same taps then spread over a
// larger disk, so k is capped at 1.5, past which the measured accuracy no
// longer gained and the noise grew (docs/radiosity.md, "The screen disk"):
//   k = min(1 / sqrt(1 - (r / z_X)^2), 1.5), and 1.5 where z_X <= r.
// B is radiance (albedo / pi * direct irradiance, as the reference's L), so no
// factor of pi enters. Layers are summed, not maxed: both are surfaces that
// send light. c is the share of the cosine-weighted hemisphere the samples
// covered (1 / pi * sum W cos), the part compose does not fill with the
// environment. Samples off the buffer, on sky or beyond r add nothing (the
// reference's L is 0 there too), rather than being renormalised away.
//
// DEEPGI_RADIOSITY_METHOD_PUBLISHED (the deep G-buffer paper's, for comparison):
//   E(X) = 2 pi / M * sum over used samples of min(B(Y) cos(theta_X), clamp)
//   c(X) = M / (taps * layers)
// M the used samples. It is not an estimate of the integral: it is 2 pi times
// the mean of B cos(theta_X) over the samples that found a surface, whatever
// solid angle each of them stands for.
#include "frame_constants.glsl"
#include "pass_parameters.h"
#include "gbuffer_encoding.glsl"
#include "pixel_rotation.glsl"
#include "radiosity_taps.glsl"
#include "rotated_grid.glsl"
#include "math_constants.glsl"

// Bindings are this shader's own; radiosity_pass.cpp binds the same numbers.
layout(binding = 10) uniform sampler2D depth_pyramid;
layout(binding = 21) uniform sampler2DArray prepared_radiance;
layout(binding = 22) uniform sampler2DArray prepared_normal;

layout(location = 4) uniform int layer;
layout(std140, binding = DEEPGI_UBO_PASS) uniform RadiosityGatherBlock {
  RadiosityGatherParameters gather;
};

layout(location = 0) out vec4 out_irradiance;  // rgb: E, a: confidence

// radiosity_sample_visible(): with visibility steps, a sample that other
// stored geometry hides from X adds nothing (docs/radiosity.md). Compiled
// into its own program (radiosity_pass.cpp), so the default one carries none
// of its code.
#if defined(RADIOSITY_VISIBILITY)
#include "radiosity_visibility.glsl"
#endif


// w_ij above without its factor r^2 (the caller's), for a sample that passed
// the facing tests. A patch seen edge-on stands for unbounded area: its weight is
// clamped as sao.frag clamps it.
float area_weight(vec3 tap_position, vec3 tap_normal, float vv, float cos_y, float depth_ratio_squared,
                  float alpha) {
  vec3 view_ray = normalize(tap_position);
  float cos_phi = -view_ray.z;
  float cos_view = max(dot(tap_normal, -view_ray), 0.1);
  return alpha * depth_ratio_squared * cos_phi * cos_y / (vv * cos_view);
}

// What every sample of one pixel shares.
struct GatherPixel {
  vec3 position;
  vec3 normal;
  float depth;
  float radius_squared;
  float area_scale;  // r^2 k^2, the factor of every area weight (w_ij above)
  bool area;
};

// The sums over the used samples.
struct GatherSum {
  vec3 sum;        // of min(B(Y) cos(theta_X) w_ij, clamp), w_ij = 1 for the published method
  float coverage;  // area: of cos(theta_X) w_ij
  int used;
};

// Sample (tap, layer j): adds it where it is used. A function called once per
// layer, not a loop over the layers: llvmpipe runs such a loop as a loop,
// with each select on the layer made at run time (as sao.frag's estimators).
void add_sample(inout GatherSum acc, GatherPixel px, ivec2 texel, int level, vec2 tap_centre,
                float alpha, float tap_depth, int j) {
  if (tap_depth <= 0.0) return;
  vec3 y = camera_position_at(tap_centre, tap_depth, frame.internal_size, frame.camera_ray_scale);
  vec3 v = y - px.position;
  float vv = dot(v, v);
  if (vv >= px.radius_squared || vv <= 0.0) return;
  vec3 w = v * inversesqrt(vv);
  float cos_x = dot(w, px.normal);
  if (cos_x <= 0.0) return;
  ivec3 at = ivec3(texel, j);
  vec3 tap_normal = decode_normal(texelFetch(prepared_normal, at, level).xy);
  float cos_y = -dot(w, tap_normal);
  if (cos_y <= 0.0) return;
#if defined(RADIOSITY_VISIBILITY)
  if (!radiosity_sample_visible(px.position, y, gather.layers, gather.visibility_steps, gather.visibility_thickness))
    return;
#endif
  float weight = 1.0;
  if (px.area) {
    float ratio = tap_depth / px.depth;
    weight = px.area_scale * area_weight(y, tap_normal, vv, cos_y, ratio * ratio, alpha);
    acc.coverage += cos_x * weight;
  }
  acc.sum += min(texelFetch(prepared_radiance, at, level).rgb * (cos_x * weight), vec3(gather.tap_clamp));
  ++acc.used;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec2 depths = texelFetch(depth_pyramid, pixel, 0).rg;
  float depth = layer == 0 ? depths.r : depths.g;
  if (depth <= 0.0) {
    out_irradiance = vec4(0.0);
    return;
  }
  float radius = gather.radius;
  float q = gather.q;
  int max_mip = gather.max_mip;
  vec3 position = camera_position_at(vec2(pixel) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
  vec3 normal = decode_normal(texelFetch(prepared_normal, ivec3(pixel, layer), 0).xy);
  bool area = gather.method == DEEPGI_RADIOSITY_METHOD_AREA;
  // The ball's projection (k above); the published method keeps the paper's disk.
  float widening = 1.0;
  if (area) {
    float t = radius / depth;
    widening = t < 1.0 ? min(inversesqrt(1.0 - t * t), 1.5) : 1.5;
  }
  float radius_pixels = widening * radius * (0.5 * frame.internal_size.y) / (frame.camera_ray_scale.y * depth);
  float radius_squared = radius * radius;
  // The per-frame angle (frame.cpp) follows a sequence that never repeats,
  // which the temporal filter averages over.
  float phi = pixel_rotation_angle(uvec2(pixel), uint(frame.rotation_seed)) + frame.temporal_angle;
  mat2 rotation = mat2(cos(phi), sin(phi), -sin(phi), cos(phi));
  ivec2 size = ivec2(frame.internal_size.xy);

  GatherPixel px;
  px.position = position;
  px.normal = normal;
  px.depth = depth;
  px.radius_squared = radius_squared;
  px.area_scale = radius_squared * (widening * widening);
  px.area = area;
  GatherSum acc;
  acc.sum = vec3(0.0);
  acc.coverage = 0.0;
  acc.used = 0;
  // This frame's radial shift s (frame.cpp, from the sequence's v): tap i
  // sits at alpha = (i + 1/2 + s) / N instead of (i + 1/2) / N, along the
  // same direction. Over frames s covers [-1/2, 1/2), so the taps' radii
  // cover [0, 1) uniformly and the weight alpha makes the frames' mean the
  // area integral over the disk, where fixed radii would average rings. s is
  // exactly 0 on the first frame: the scale is then exactly 1.
  float radial_shift = frame.temporal_sample.z;
  for (int i = 0; i < RADIOSITY_NUM_TAPS; ++i) {
    // (i + 1/2 + s) / N = alpha_i (1 + s / (i + 1/2)): one scale for the radius and the offset.
    float radial_scale = 1.0 + radial_shift / (float(i) + 0.5);
    float alpha = RADIOSITY_TAP_ALPHAS[i] * radial_scale;
    vec2 offset = clamp((rotation * (RADIOSITY_TAP_OFFSETS[i] * radial_scale)) * radius_pixels,
                        vec2(-65536.0), vec2(65536.0));
    ivec2 tap = ivec2(floor(vec2(pixel) + 0.5 + offset));
    if (any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, size))) continue;
    // floor(log2(x)) of x >= 1 is the highest set bit of floor(x) (as sao.frag).
    float steps = min(alpha * radius_pixels / q, 65536.0);
    int level = steps < 1.0 ? 0 : min(findMSB(uint(steps)), max_mip);
    // Level sizes computed, not asked of textureSize() (llvmpipe, sao.frag).
    ivec2 texel = min(tap >> level, max(size >> level, ivec2(1)) - 1);
    vec2 tap_depths = texelFetch(depth_pyramid, texel, level).rg;
    vec2 tap_centre = vec2(rotated_grid_source_pixel(texel, level, size)) + 0.5;
    add_sample(acc, px, texel, level, tap_centre, alpha, tap_depths.r, 0);
    if (gather.layers > 1) add_sample(acc, px, texel, level, tap_centre, alpha, tap_depths.g, 1);
  }
  if (px.area) {
    float scale = two_pi / float(RADIOSITY_NUM_TAPS);
    out_irradiance = vec4(acc.sum * scale, min(acc.coverage * (2.0 / float(RADIOSITY_NUM_TAPS)), 1.0));
    return;
  }
  float samples = float(RADIOSITY_NUM_TAPS * gather.layers);
  vec3 irradiance = acc.used > 0 ? acc.sum * (two_pi / float(acc.used)) : vec3(0.0);
  out_irradiance = vec4(irradiance, float(acc.used) / samples);
}
