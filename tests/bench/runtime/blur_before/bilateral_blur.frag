#version 450 core
// The bilateral blur as it was before the key pass and the shared blur
// (verbatim from the commit before them), for blur_bench's "before" column.
// Edge-aware separable blur (design.md 3, step 5): one direction per draw,
// Gaussian weights from the generated blur_kernel.glsl, each tap further
// weighted by how well its depth, normal and position agree with the centre's
// surface, then renormalised. It blurs whatever the source texture holds (AO
// visibility, radiosity), keyed on layer 0 of the depth pyramid and G-buffer.
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"
#include "blur_kernel.glsl"

layout(binding = DEEPGI_UNIT_BLUR_SOURCE) uniform sampler2D source;
layout(binding = DEEPGI_UNIT_DEPTH_PYRAMID) uniform sampler2D depth_key;  // level 0, R: layer-0 linear depth
layout(binding = DEEPGI_UNIT_GBUFFER_NORMAL) uniform sampler2DArray gbuffer_normal;

layout(location = DEEPGI_UNIFORM_BLUR_DIRECTION) uniform ivec2 direction;
// x: depth tolerance (fraction of the centre depth), y: normal power,
// z: tangent-plane tolerance (fraction of the centre depth)
layout(location = DEEPGI_UNIFORM_BLUR_PARAMETERS) uniform vec4 blur_parameters;

layout(location = 0) out vec4 out_value;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 centre_value = texelFetch(source, pixel, 0);
  float depth = texelFetch(depth_key, pixel, 0).r;
  if (depth <= 0.0) {  // sky and background pass through
    out_value = centre_value;
    return;
  }
  // Tolerances scale with depth: a pixel covers more metres further away.
  float depth_tolerance = blur_parameters.x * depth;
  float normal_power = blur_parameters.y;
  float plane_tolerance = blur_parameters.z * depth;
  vec3 position = camera_position_at(vec2(pixel) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
  vec3 normal = decode_normal(texelFetch(gbuffer_normal, ivec3(pixel, 0), 0).xy);
  ivec2 size = textureSize(source, 0);

  float total_weight = BLUR_WEIGHTS[BLUR_RADIUS];
  vec4 sum = centre_value * total_weight;
  for (int k = -BLUR_RADIUS; k <= BLUR_RADIUS; ++k) {
    ivec2 tap = pixel + k * direction;
    if (k == 0 || any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, size))) continue;
    float tap_depth = texelFetch(depth_key, tap, 0).r;
    if (tap_depth <= 0.0) continue;
    vec3 tap_normal = decode_normal(texelFetch(gbuffer_normal, ivec3(tap, 0), 0).xy);
    vec3 tap_position = camera_position_at(vec2(tap) + 0.5, tap_depth, frame.internal_size, frame.camera_ray_scale);
    float depth_weight = max(0.0, 1.0 - abs(tap_depth - depth) / depth_tolerance);
    float normal_weight = pow(max(dot(tap_normal, normal), 0.0), normal_power);
    float plane_weight = max(0.0, 1.0 - abs(dot(tap_position - position, normal)) / plane_tolerance);
    float weight = BLUR_WEIGHTS[k + BLUR_RADIUS] * depth_weight * normal_weight * plane_weight;
    sum += texelFetch(source, tap, 0) * weight;
    total_weight += weight;
  }
  out_value = sum / total_weight;
}
