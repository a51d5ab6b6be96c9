#version 450 core
// Temporal filter of deep radiosity (design.md 3, step 7) for one layer:
// reprojects last frame's filtered E to this pixel and blends
//   E = mix(E_raw, E_history, alpha)
// keeping history only where last frame saw the same surface: its stored
// linear depth within 5% of where this point sat in the previous camera and
// its normal within about 25 degrees. Elsewhere (disocclusion, a cut, the
// first frame) the pixel starts fresh from the raw gather. The scenes are
// static, so reprojection uses the camera motion, which is what the
// G-buffer's motion vectors hold for layer 0, and works for layer 1 too.
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"

layout(binding = DEEPGI_UNIT_GBUFFER_NORMAL) uniform sampler2DArray gbuffer_normal;
layout(binding = DEEPGI_UNIT_GBUFFER_DEPTH) uniform sampler2DArray gbuffer_depth;
layout(binding = DEEPGI_UNIT_RADIOSITY_RAW_LAYER0) uniform sampler2D raw_irradiance;
layout(binding = DEEPGI_UNIT_RADIOSITY_PREVIOUS_LAYER0) uniform sampler2D history_irradiance;
layout(binding = DEEPGI_UNIT_RADIOSITY_HISTORY_KEY) uniform sampler2D history_key;

layout(location = DEEPGI_UNIFORM_LAYER) uniform int layer;
layout(location = DEEPGI_UNIFORM_RADIOSITY_ALPHA) uniform float alpha;
// This frame's camera space -> the previous frame's camera space.
layout(location = DEEPGI_UNIFORM_RADIOSITY_TO_PREVIOUS) uniform mat4 to_previous;

layout(location = 0) out vec4 out_irradiance;  // rgb: E, a: confidence
layout(location = 1) out vec4 out_key;         // x: linear depth, yz: octahedral normal

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 raw = texelFetch(raw_irradiance, pixel, 0);
  float stored = texelFetch(gbuffer_depth, ivec3(pixel, layer), 0).r;
  out_irradiance = raw;
  out_key = vec4(0.0);
  if (stored <= 0.0) return;
  float depth = frame.camera_ray_scale.z / stored;
  vec3 position = camera_position_at(vec2(pixel) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
  vec2 encoded_normal = texelFetch(gbuffer_normal, ivec3(pixel, layer), 0).xy;
  out_key = vec4(depth, encoded_normal, 0.0);
  if (alpha <= 0.0) return;

  vec3 previous_position = (to_previous * vec4(position, 1.0)).xyz;
  vec4 clip = frame.projection * vec4(previous_position, 1.0);
  if (clip.w <= 0.0) return;
  vec2 previous_pixel = (clip.xy / clip.w * 0.5 + 0.5) * frame.internal_size.xy;
  ivec2 texel = ivec2(floor(previous_pixel));
  if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(frame.internal_size.xy)))) return;
  vec4 key = texelFetch(history_key, texel, 0);
  float expected_depth = -previous_position.z;
  if (key.x <= 0.0 || abs(key.x - expected_depth) > 0.05 * expected_depth) return;
  vec3 previous_normal = mat3(to_previous) * decode_normal(encoded_normal);
  if (dot(decode_normal(key.yz), previous_normal) < 0.9) return;
  out_irradiance = mix(raw, texelFetch(history_irradiance, texel, 0), alpha);
}
