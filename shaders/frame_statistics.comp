#version 450 core
// Frame statistics over the viewport (guard band left out, as the tonemap
// crops it): the log-average luminance of the lit HDR image before the
// tonemap, the exposure in use, and each G-buffer layer's depth range.
//
// Two stages of one reduction, each a fixed tree in a fixed order, so the
// same frame gives the same bits every run:
// - FRAME_STATISTICS_PARTIALS: one 16x16 group per 64x64 tile (each
//   invocation sums a 4x4 block first: fewer groups and barriers, which is
//   what a group costs on a CPU rasteriser) writes its sums to `partials`;
// - otherwise one group of 256 invocations sums the partials and writes the
//   2x1 `statistics` image the tonemap and the debug view read:
//   texel 0 (exposure in use, log-average luminance over the pixels where
//   layer 0 holds a surface (every pixel where none does), unsmoothed auto
//   exposure, pixels averaged), texel 1 (layer 0 near, far, layer 1 near, far) in
//   metres, 0 where a layer holds nothing.
#include "frame_constants.glsl"

#ifdef FRAME_STATISTICS_PARTIALS
layout(local_size_x = 16, local_size_y = 16) in;
#else
layout(local_size_x = 256) in;
#endif
const uint GROUP_INVOCATIONS = 256u;

// Bindings are this shader's own; frame_statistics_pass.cpp binds the same numbers.
layout(binding = 8) uniform sampler2D composed_radiance;
layout(binding = 4) uniform sampler2DArray gbuffer_depth;
layout(binding = 0, rgba32f) uniform image2D statistics;

struct Partial {
  float log_sum;  // sum of log(delta + luminance) over pixels where layer 0 holds a surface
  float pixels;
  float near0, far0, near1, far1;  // linear depth; near = NO_NEAR, far = 0 where empty
  float all_log_sum;  // the same over every pixel, for a frame without any surface
  float all_pixels;
};
layout(std430, binding = 0) buffer Partials { Partial partials[]; };

// Uniforms: the auto exposure's key and clamp, and whether to start the
// smoothing afresh (history invalidated, or the last frame was not auto).
layout(location = 0) uniform float key;
layout(location = 1) uniform vec2 exposure_limits;
layout(location = 2) uniform int restart;
layout(location = 3) uniform float smoothing;  // share of the new value per frame
layout(location = 4) uniform int partial_count;

const float NO_NEAR = 3.0e38;
// Keeps log() finite on black pixels (Reinhard et al. 2002's delta).
const float LOG_DELTA = 1.0e-4;
const vec3 LUMINANCE = vec3(0.2126, 0.7152, 0.0722);  // Rec. 709

shared Partial group_sums[GROUP_INVOCATIONS];

Partial empty_partial() { return Partial(0.0, 0.0, NO_NEAR, 0.0, NO_NEAR, 0.0, 0.0, 0.0); }

Partial combine(Partial a, Partial b) {
  return Partial(a.log_sum + b.log_sum, a.pixels + b.pixels, min(a.near0, b.near0), max(a.far0, b.far0),
                 min(a.near1, b.near1), max(a.far1, b.far1), a.all_log_sum + b.all_log_sum,
                 a.all_pixels + b.all_pixels);
}

#ifdef FRAME_STATISTICS_PARTIALS
Partial pixel_partial(ivec2 pixel) {
  Partial p = empty_partial();
  ivec2 viewport = ivec2(frame.viewport_width, frame.viewport_height);
  if (any(greaterThanEqual(pixel, viewport))) return p;
  ivec2 texel = pixel + ivec2(frame.guard_band);
  float luminance = max(dot(texelFetch(composed_radiance, texel, 0).rgb, LUMINANCE), 0.0);
  p.all_log_sum = log(LOG_DELTA + luminance);
  p.all_pixels = 1.0;
  float stored0 = texelFetch(gbuffer_depth, ivec3(texel, 0), 0).r;
  float stored1 = texelFetch(gbuffer_depth, ivec3(texel, 1), 0).r;
  // The exposure is for the lit surfaces: the background (cornell's black
  // beyond the open side, atrium's sky) is a constant the light never
  // reaches, and a black one would drag the log-average towards log(delta).
  if (stored0 > 0.0) {
    p.log_sum = p.all_log_sum;
    p.pixels = 1.0;
  }
  if (stored0 > 0.0) p.near0 = p.far0 = frame.camera_ray_scale.z / stored0;
  if (stored1 > 0.0) p.near1 = p.far1 = frame.camera_ray_scale.z / stored1;
  return p;
}
#endif

void main() {
  uint index = gl_LocalInvocationIndex;
#ifdef FRAME_STATISTICS_PARTIALS
  Partial block = empty_partial();
  ivec2 corner = ivec2(gl_GlobalInvocationID.xy) * 4;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) block = combine(block, pixel_partial(corner + ivec2(x, y)));
  group_sums[index] = block;
#else
  Partial sum = empty_partial();
  for (int i = int(index); i < partial_count; i += int(GROUP_INVOCATIONS)) sum = combine(sum, partials[i]);
  group_sums[index] = sum;
#endif
  barrier();
  for (uint stride = GROUP_INVOCATIONS / 2u; stride > 0u; stride /= 2u) {
    if (index < stride) group_sums[index] = combine(group_sums[index], group_sums[index + stride]);
    barrier();
  }
  if (index != 0u) return;
  Partial total = group_sums[0];
#ifdef FRAME_STATISTICS_PARTIALS
  partials[gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x] = total;
#else
  float log_average = total.pixels > 0.0 ? exp(total.log_sum / total.pixels)
                                         : exp(total.all_log_sum / max(total.all_pixels, 1.0));
  float target = clamp(key / log_average, exposure_limits.x, exposure_limits.y);
  float exposure = frame.exposure;  // a manual exposure is used as given
  if (exposure <= 0.0) {
    // Smoothed in log space, so a step up and a step down of the same ratio
    // take the same number of frames.
    float previous = imageLoad(statistics, ivec2(0, 0)).x;
    exposure = restart != 0 || !(previous > 0.0) ? target : exp(mix(log(previous), log(target), smoothing));
  }
  imageStore(statistics, ivec2(0, 0), vec4(exposure, log_average, target, total.pixels > 0.0 ? total.pixels : total.all_pixels));
  bool has0 = total.far0 > 0.0, has1 = total.far1 > 0.0;
  imageStore(statistics, ivec2(1, 0),
             vec4(has0 ? total.near0 : 0.0, total.far0, has1 ? total.near1 : 0.0, total.far1));
#endif
}
