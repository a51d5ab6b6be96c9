#version 450 core
// Temporal filter of deep radiosity (docs/design.md, section 5.9) for one layer: finds
// last frame's E of this pixel's surface point with the G-buffer's motion
// vectors, rejects it where depth or normal disagree
// (history_reprojection.glsl), and accumulates a running mean where the
// point is still and an exponential blend where it moves
// (temporal_accumulation.glsl). A rejected pixel starts fresh from the raw
// gather.
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"
#include "history_reprojection.glsl"
#include "temporal_accumulation.glsl"

// Bindings are this shader's own; radiosity_pass.cpp binds the same numbers.
layout(binding = 0) uniform sampler2DArray gbuffer_normal;
layout(binding = 3) uniform sampler2DArray gbuffer_motion;
layout(binding = 10) uniform sampler2D depth_pyramid;
layout(binding = 17) uniform sampler2D raw_irradiance;
layout(binding = 15) uniform sampler2D history_irradiance;
layout(binding = 19) uniform sampler2D history_key;

layout(location = 4) uniform int layer;
layout(location = 29) uniform float alpha;
// 1 on the frame the key light changed: every pixel blends as a moving one,
// so the running mean of the old lighting does not linger for ~CAP frames.
layout(location = 30) uniform int lighting_changed;

layout(location = 0) out vec4 out_irradiance;  // rgb: E, a: confidence
layout(location = 1) out vec4 out_key;         // history_reprojection.glsl

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 raw = texelFetch(raw_irradiance, pixel, 0);
  vec2 depths = texelFetch(depth_pyramid, pixel, 0).rg;
  float depth = layer == 0 ? depths.r : depths.g;
  out_irradiance = raw;
  out_key = vec4(0.0);
  if (depth <= 0.0) return;
  vec3 normal = decode_normal(texelFetch(gbuffer_normal, ivec3(pixel, layer), 0).xy);
  ivec2 texel;
  vec4 key;
  Accumulation result;
  if (find_history(pixel, layer, normal, gbuffer_motion, history_key, texel, key)) {
    result = accumulate(raw, texelFetch(history_irradiance, texel, 0), key.w, alpha,
                        lighting_changed == 0 && history_still(pixel, layer, gbuffer_motion));
  } else {
    result = accumulate(raw, raw, 0.0, alpha, false);
  }
  out_irradiance = result.mean;
  out_key = history_key_for(depth, normal, result.count);
}
