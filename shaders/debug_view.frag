#version 450 core
// Shows one attachment of one layer instead of the final image (guard band
// cropped like the tonemap). Nothing hit shows as black.
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"
#include "math_constants.glsl"
#include "tonemap_curve.glsl"

// Bindings are this shader's own; debug_view_pass.cpp binds the same numbers.
layout(binding = 0) uniform sampler2DArray gbuffer_normal;
layout(binding = 1) uniform sampler2DArray gbuffer_albedo;
layout(binding = 2) uniform sampler2DArray gbuffer_emissive;
layout(binding = 3) uniform sampler2DArray gbuffer_motion;
layout(binding = 4) uniform sampler2DArray gbuffer_depth;
layout(binding = 7) uniform sampler2DArray direct_light;
layout(binding = 13) uniform sampler2D ao_raw;
layout(binding = 11) uniform sampler2D ao_blurred;
layout(binding = 28) uniform sampler2D ao_temporal;
layout(binding = 21) uniform sampler2DArray prepared_radiance;
layout(binding = 14) uniform sampler2D radiosity_blurred;
layout(binding = 17) uniform sampler2D radiosity_layer0;
layout(binding = 18) uniform sampler2D radiosity_layer1;
// frame_statistics.comp's result: the exposure in use (texel 0, x) and each
// layer's near and far depth (texel 1).
layout(binding = 9) uniform sampler2D frame_statistics;

// The reflection pass's hit texture, bound only while that pass runs
// (debug_view_pass.cpp declares unit 5 for it; frame.reflection_term says
// whether it does).
layout(binding = 5) uniform sampler2D reflection_hit;

layout(location = 0) out vec4 out_colour;

// Mirror pixels by the layer their reflected ray hit: none (environment)
// blue, layer 0 green, layer 1 red; other surfaces dim grey.
vec3 reflection_hit_colour(ivec2 pixel) {
  vec3 grey = vec3(0.3 * dot(srgb_decode(texelFetch(gbuffer_albedo, ivec3(pixel, 0), 0).rgb), vec3(1.0 / 3.0)));
  if (frame.reflection_term == 0) return grey;
  float layer = texelFetch(reflection_hit, pixel, 0).z;
  if (layer < -1.5) return grey;
  if (layer < -0.5) return vec3(0.1, 0.2, 0.9);
  return layer < 0.5 ? vec3(0.1, 0.8, 0.2) : vec3(0.95, 0.15, 0.1);
}

vec3 view_colour(ivec2 pixel, int view) {
  float exposure = texelFetch(frame_statistics, ivec2(0, 0), 0).x;
  int layer = (view == DEEPGI_VIEW_NORMAL_LAYER1 || view == DEEPGI_VIEW_ALBEDO_LAYER1 ||
               view == DEEPGI_VIEW_DEPTH_LAYER1 || view == DEEPGI_VIEW_DIRECT_LAYER1 ||
               view == DEEPGI_VIEW_RADIOSITY_LAYER1) ? 1 : 0;
  ivec3 texel = ivec3(pixel, layer);
  float stored_depth = texelFetch(gbuffer_depth, texel, 0).r;
  if (stored_depth <= 0.0) return vec3(0.0);
  // Visibility is shown as compose uses it (1 = unoccluded white), not
  // tonemapped: the solid-angle AV is signed until here, so clamp to [0, 1].
  if (view == DEEPGI_VIEW_REFLECTION_HIT_LAYER) return reflection_hit_colour(pixel);
  if (view == DEEPGI_VIEW_AO_RAW) return vec3(clamp(texelFetch(ao_raw, pixel, 0).r, 0.0, 1.0));
  if (view == DEEPGI_VIEW_AO_BLURRED) return vec3(clamp(texelFetch(ao_blurred, pixel, 0).r, 0.0, 1.0));
  if (view == DEEPGI_VIEW_AO_TEMPORAL) return vec3(clamp(texelFetch(ao_temporal, pixel, 0).r, 0.0, 1.0));
  if (view == DEEPGI_VIEW_RADIOSITY_PREPARED)
    return filmic_tonemap(texelFetch(prepared_radiance, ivec3(pixel, 0), 0).rgb * exposure);
  // Irradiance E is shown as the radiance of a white Lambertian surface, E / pi.
  if (view == DEEPGI_VIEW_RADIOSITY_LAYER0)
    return filmic_tonemap(texelFetch(radiosity_layer0, pixel, 0).rgb * (exposure * inv_pi));
  if (view == DEEPGI_VIEW_RADIOSITY_LAYER1)
    return filmic_tonemap(texelFetch(radiosity_layer1, pixel, 0).rgb * (exposure * inv_pi));
  if (view == DEEPGI_VIEW_RADIOSITY_BLURRED)
    return filmic_tonemap(texelFetch(radiosity_blurred, pixel, 0).rgb * (exposure * inv_pi));
  if (view == DEEPGI_VIEW_RADIOSITY_CONFIDENCE) return vec3(texelFetch(radiosity_layer0, pixel, 0).a);
  if (view == DEEPGI_VIEW_NORMAL_LAYER0 || view == DEEPGI_VIEW_NORMAL_LAYER1)
    return decode_normal(texelFetch(gbuffer_normal, texel, 0).xy) * 0.5 + 0.5;
  if (view == DEEPGI_VIEW_ALBEDO_LAYER0 || view == DEEPGI_VIEW_ALBEDO_LAYER1)
    return srgb_decode(texelFetch(gbuffer_albedo, texel, 0).rgb);
  if (view == DEEPGI_VIEW_EMISSIVE)
    return filmic_tonemap(texelFetch(gbuffer_emissive, texel, 0).rgb * exposure);
  if (view == DEEPGI_VIEW_MOTION) {
    vec2 motion = texelFetch(gbuffer_motion, texel, 0).xy;
    return vec3(clamp(0.5 + motion / 32.0, 0.0, 1.0), 0.5);
  }
  if (view == DEEPGI_VIEW_DEPTH_LAYER0 || view == DEEPGI_VIEW_DEPTH_LAYER1) {
    // Scaled by this layer's own near and far depth (frame_statistics), so
    // a layer that spans 0.4 m uses the whole grey ramp as one that spans
    // 40 m does: near white, far 0.1 (black stays "nothing"). The grey is
    // linear in depth on the display (decoded here, encoded in main).
    float depth = frame.camera_ray_scale.z / stored_depth;
    vec4 ranges = texelFetch(frame_statistics, ivec2(1, 0), 0);
    vec2 range = layer == 0 ? ranges.xy : ranges.zw;
    float t = clamp((depth - range.x) / max(range.y - range.x, 1e-6 * range.y), 0.0, 1.0);
    return srgb_decode(vec3(1.0 - 0.9 * t));
  }
  return filmic_tonemap(texelFetch(direct_light, texel, 0).rgb * exposure);
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy) + ivec2(frame.guard_band);
  out_colour = vec4(srgb_encode(view_colour(pixel, frame.debug_view)), 1.0);
}
