#version 450 core
// Temporal filter of the ambient visibility: the raw SAO result of this frame
// (its taps turned by this frame's point of the temporal sequence)
// accumulated with the reprojected history exactly as the radiosity temporal
// filter does (history_reprojection.glsl, temporal_accumulation.glsl).
// The solid-angle visibility is signed (sao.frag): the means here are linear,
// so negative samples average with the rest and nothing clamps them.
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"
#include "history_reprojection.glsl"
#include "temporal_accumulation.glsl"

// Bindings are this shader's own; ao_temporal_pass.cpp binds the same numbers.
layout(binding = 0) uniform sampler2DArray gbuffer_normal;
layout(binding = 3) uniform sampler2DArray gbuffer_motion;
layout(binding = 10) uniform sampler2D depth_pyramid;
layout(binding = 13) uniform sampler2D raw_visibility;
// x: filtered visibility (R32F: a running mean of up to DEEPGI_TEMPORAL_CAP
// frames moves by less than half a float16 step near 1)
layout(binding = 11) uniform sampler2D history_visibility;
layout(binding = 19) uniform sampler2D history_key;

layout(location = 29) uniform float alpha;

layout(location = 0) out vec4 out_visibility;  // x: filtered
layout(location = 1) out vec4 out_key;         // history_reprojection.glsl

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float raw = texelFetch(raw_visibility, pixel, 0).r;
  float depth = texelFetch(depth_pyramid, pixel, 0).r;
  out_visibility = vec4(raw, 0.0, 0.0, 0.0);
  out_key = vec4(0.0);
  if (depth <= 0.0) return;
  vec3 normal = decode_normal(texelFetch(gbuffer_normal, ivec3(pixel, 0), 0).xy);
  ivec2 texel;
  vec4 key;
  Accumulation result;
  vec4 raw4 = vec4(raw);
  if (find_history(pixel, 0, normal, gbuffer_motion, history_key, texel, key)) {
    float history = texelFetch(history_visibility, texel, 0).x;
    result = accumulate(raw4, vec4(history), key.w, alpha, history_still(pixel, 0, gbuffer_motion));
  } else {
    result = accumulate(raw4, raw4, 0.0, alpha, false);
  }
  out_visibility = vec4(result.mean.x, 0.0, 0.0, 0.0);
  out_key = history_key_for(depth, normal, result.count);
}
