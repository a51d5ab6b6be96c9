#version 450 core
// Radiosity prepare (docs/design.md, section 5.8): what the gather reads at a
// tap, for both G-buffer layers, as rotated-grid MIP levels like the depth
// pyramid, so far taps read a coarser level (fewer cache misses) and each tap
// costs two fetches per layer instead of six.
//
// Level 0, per layer j: the outgoing radiance
//   B = (direct + rho_prop * albedo / pi * E_prev) * boost(albedo) + emissive
// (emissive on layer 0 only: the G-buffer stores none for layer 1), E_prev
// being last frame's filtered E reprojected with the motion vectors
// (history_reprojection.glsl; 0 where history is rejected, so a disoccluded
// pixel starts with one bounce), and the octahedral normal.
// Level m + 1 keeps one texel of each 2x2 block of level m, the same corner
// as depth_pyramid.comp (rotated_grid.glsl), so texel t of level m holds the
// normal and depth of one and the same level-0 pixel, the texel's
// representative. Its radiance is, with `prefilter` on (the default), the
// mean over the block's texels that lie on the representative's surface,
// each weighted by the share of its block's level-0 pixels it stands for
// (radiance.a, 1 at level 0; a share, not a count, so that it stays within
// a half float at every level a 16384-pixel image has): a coarse
// tap then reads the light of the area it stands for, not one pixel of a
// lattice fixed in the image that the frames never average away. "On the
// surface" is a normal within about 25 degrees (cosine 0.9) and a position
// within about 6 degrees of the representative's tangent plane as seen from
// it (|n . d| <= 0.1 |d|): a plain mean would mix a foreground's radiance
// into a background's (docs/radiosity.md, "Prefiltered levels").
//
// Variant PREPARE_BASE_LEVEL writes level 0; the other variant writes a level
// from the level above it.
#include "frame_constants.glsl"
#include "pass_parameters.h"
#include "gbuffer_encoding.glsl"
#include "history_reprojection.glsl"
#include "rotated_grid.glsl"
#include "math_constants.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// Bindings are this shader's own; radiosity_prepare_pass.cpp binds the same numbers.
layout(binding = 1, rgba16f) uniform writeonly image2DArray radiance_destination;
layout(binding = 3, rg16f) uniform writeonly image2DArray normal_destination;

#ifdef PREPARE_BASE_LEVEL
layout(binding = 0) uniform sampler2DArray gbuffer_normal;
layout(binding = 1) uniform sampler2DArray gbuffer_albedo;
layout(binding = 2) uniform sampler2DArray gbuffer_emissive;
layout(binding = 3) uniform sampler2DArray gbuffer_motion;
layout(binding = 4) uniform sampler2DArray gbuffer_depth;
layout(binding = 7) uniform sampler2DArray direct_light;
layout(binding = 15) uniform sampler2D previous_irradiance0;
layout(binding = 16) uniform sampler2D previous_irradiance1;
layout(binding = 19) uniform sampler2D history_key0;
layout(binding = 20) uniform sampler2D history_key1;
#else
layout(binding = 0, rgba16f) uniform readonly image2DArray radiance_source;
layout(binding = 2, rg16f) uniform readonly image2DArray normal_source;
layout(binding = 5) uniform sampler2D depth_pyramid;  // the sources' depths, at source_level
layout(location = 0) uniform int source_level;        // the level read; this dispatch writes the next
#endif
// Every variant reads the block: the base level its boost and rho_prop, the
// others `prefilter`.
layout(std140, binding = DEEPGI_UBO_PASS) uniform RadiosityPrepareBlock {
  RadiosityPrepareParameters prepare;
};


#ifdef PREPARE_BASE_LEVEL
// (max_c rho - min_c rho) / max_c rho blended with 1 by `amount`.
float boost(vec3 rho, float amount) {
  float high = max(rho.r, max(rho.g, rho.b));
  float low = min(rho.r, min(rho.g, rho.b));
  float saturation = high > 0.0 ? (high - low) / high : 0.0;
  return mix(1.0, saturation, amount);
}

// Last frame's filtered E of the point seen at `pixel`, or 0 without history.
vec3 previous_irradiance(ivec2 pixel, int layer, vec3 normal) {
  ivec2 texel;
  vec4 key;
  if (layer == 0) {
    if (!find_history(pixel, 0, normal, gbuffer_motion, history_key0, texel, key)) return vec3(0.0);
    return texelFetch(previous_irradiance0, texel, 0).rgb;
  }
  if (!find_history(pixel, 1, normal, gbuffer_motion, history_key1, texel, key)) return vec3(0.0);
  return texelFetch(previous_irradiance1, texel, 0).rgb;
}
#else
// Camera-space position of the level-0 pixel that texel `at` of the source
// level stands for, at its stored depth.
vec3 source_position(ivec2 at, float depth) {
  ivec2 pixel = rotated_grid_source_pixel(at, source_level, ivec2(frame.internal_size.xy));
  return camera_position_at(vec2(pixel) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
}

// Radiance (rgb) and weight (a: the share of its block's level-0 pixels it
// stands for) of texel `texel` of the next level from its 2x2 block at the
// source level, whose texel `chosen` is the representative.
vec4 reduced_radiance(ivec2 texel, ivec2 chosen, int layer) {
  vec4 kept = imageLoad(radiance_source, ivec3(chosen, layer));
  if (prepare.prefilter == 0.0 || kept.a <= 0.0) return kept;
  ivec2 size = imageSize(radiance_source).xy;
  vec3 normal = decode_normal(imageLoad(normal_source, ivec3(chosen, layer)).xy);
  vec3 position = source_position(chosen, texelFetch(depth_pyramid, chosen, source_level)[layer]);
  vec4 sum = vec4(0.0);
  for (int j = 0; j < 4; ++j) {
    ivec2 at = 2 * texel + ivec2(j & 1, j >> 1);
    if (any(greaterThanEqual(at, size))) continue;
    // The representative passes its own test (d = 0): its values are read.
    if (at == chosen) {
      sum += vec4(kept.rgb * kept.a, kept.a);
      continue;
    }
    vec4 radiance = imageLoad(radiance_source, ivec3(at, layer));
    if (radiance.a <= 0.0) continue;
    vec3 d = source_position(at, texelFetch(depth_pyramid, at, source_level)[layer]) - position;
    vec3 n = decode_normal(imageLoad(normal_source, ivec3(at, layer)).xy);
    if (dot(n, normal) < 0.9 || abs(dot(normal, d)) > 0.1 * length(d)) continue;
    sum += vec4(radiance.rgb * radiance.a, radiance.a);
  }
  // The representative is one of the four (clamped at an odd edge, it is
  // the block's own edge texel), so sum.a > 0.
  return vec4(sum.rgb / sum.a, 0.25 * sum.a);
}
#endif

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(radiance_destination).xy))) return;
  for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
#ifdef PREPARE_BASE_LEVEL
    ivec3 at = ivec3(texel, layer);
    vec4 radiance = vec4(0.0);
    vec2 encoded_normal = texelFetch(gbuffer_normal, at, 0).xy;
    if (texelFetch(gbuffer_depth, at, 0).r > 0.0) {
      float rho_prop = prepare.rho_prop;
      vec3 rho = srgb_decode(texelFetch(gbuffer_albedo, at, 0).rgb);
      vec3 bounce = vec3(0.0);
      if (rho_prop > 0.0) bounce = rho_prop * inv_pi * rho * previous_irradiance(texel, layer, decode_normal(encoded_normal));
      radiance.rgb = (texelFetch(direct_light, at, 0).rgb + bounce) * boost(rho, prepare.boost);
      if (layer == 0) radiance.rgb += texelFetch(gbuffer_emissive, at, 0).rgb;
      radiance.a = 1.0;
    }
    imageStore(radiance_destination, at, radiance);
    imageStore(normal_destination, at, vec4(encoded_normal, 0.0, 0.0));
#else
    ivec2 from = min(2 * texel + rotated_grid_corner(texel), imageSize(radiance_source).xy - 1);
    imageStore(radiance_destination, ivec3(texel, layer), reduced_radiance(texel, from, layer));
    imageStore(normal_destination, ivec3(texel, layer), imageLoad(normal_source, ivec3(from, layer)));
#endif
  }
}
