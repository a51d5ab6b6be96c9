#version 450 core
// Temporal filter of the mirror reflections (reflection_temporal_pass.cpp,
// docs/reflections.md "Temporal filter"). Each frame's march takes a new step
// offset from the frame sequence, so at a still camera the frames are samples
// of the integral over the offsets and their running mean converges to it
// (temporal_accumulation.glsl, the same cap as AO and radiosity).
// Under motion, and on the frame the key light changes, the history is dropped: the reflected point moves with the
// reflected geometry, not with the mirror's surface, so the mirror's motion
// vectors would smear the reflection into a trail.
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"
#include "history_reprojection.glsl"
#include "temporal_accumulation.glsl"

// Bindings are this shader's own; reflection_temporal_pass.cpp binds the same numbers.
layout(binding = 0) uniform sampler2DArray gbuffer_normal;
layout(binding = 1) uniform sampler2DArray gbuffer_motion;
layout(binding = 2) uniform sampler2D depth_pyramid;
layout(binding = 3) uniform sampler2D raw_reflection;  // rgb radiance, a hit weight
layout(binding = 4) uniform sampler2D history_reflection;
layout(binding = 5) uniform sampler2D history_key;

// 1 on the frame the key light changed: the lit radiance the history holds is
// stale, so this frame's march stands alone.
layout(location = 0) uniform int lighting_changed;

layout(location = 0) out vec4 out_reflection;  // the filtered rgb and weight
layout(location = 1) out vec4 out_key;         // history_reprojection.glsl

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 raw = texelFetch(raw_reflection, pixel, 0);
  float depth = texelFetch(depth_pyramid, pixel, 0).r;
  out_reflection = raw;
  out_key = vec4(0.0);
  if (depth <= 0.0) return;
  vec3 normal = decode_normal(texelFetch(gbuffer_normal, ivec3(pixel, 0), 0).xy);
  ivec2 texel;
  vec4 key;
  float count = 1.0;
  if (lighting_changed == 0 && history_still(pixel, 0, gbuffer_motion) &&
      find_history(pixel, 0, normal, gbuffer_motion, history_key, texel, key)) {
    Accumulation result = accumulate(raw, texelFetch(history_reflection, texel, 0), key.w, 1.0, true);
    out_reflection = result.mean;
    count = result.count;
  }
  out_key = history_key_for(depth, normal, count);
}
