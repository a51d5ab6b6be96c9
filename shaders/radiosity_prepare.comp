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
// Level m + 1 copies one texel of each 2x2 block of level m, the same corner
// as depth_pyramid.comp (rotated_grid.glsl), so texel t of level m holds
// radiance, normal and depth of one and the same level-0 pixel. Averaging
// would mix the radiance of a foreground and a background.
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
// The boost amount and rho_prop (pass_parameters.h).
layout(std140, binding = DEEPGI_UBO_PASS) uniform RadiosityPrepareBlock {
  RadiosityPrepareParameters prepare;
};
#else
layout(binding = 0, rgba16f) uniform readonly image2DArray radiance_source;
layout(binding = 2, rg16f) uniform readonly image2DArray normal_source;
#endif


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
    imageStore(radiance_destination, ivec3(texel, layer), imageLoad(radiance_source, ivec3(from, layer)));
    imageStore(normal_destination, ivec3(texel, layer), imageLoad(normal_source, ivec3(from, layer)));
#endif
  }
}
