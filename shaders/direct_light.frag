#version 450 core
// Lambertian direct light of one G-buffer layer (uniform `layer`) into HDR.
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"
#include "lighting.glsl"

layout(binding = DEEPGI_UNIT_GBUFFER_NORMAL) uniform sampler2DArray gbuffer_normal;
layout(binding = DEEPGI_UNIT_GBUFFER_ALBEDO) uniform sampler2DArray gbuffer_albedo;
layout(binding = DEEPGI_UNIT_GBUFFER_DEPTH) uniform sampler2DArray gbuffer_depth;
layout(location = DEEPGI_UNIFORM_LAYER) uniform int layer;

layout(location = 0) out vec3 out_radiance;

void main() {
  ivec3 texel = ivec3(gl_FragCoord.xy, layer);
  float stored_depth = texelFetch(gbuffer_depth, texel, 0).r;
  if (stored_depth <= 0.0) {
    out_radiance = vec3(0.0);
    return;
  }
  float depth = frame.camera_ray_scale.z / stored_depth;
  vec3 position = camera_position_at(gl_FragCoord.xy, depth, frame.internal_size, frame.camera_ray_scale);
  vec3 normal = decode_normal(texelFetch(gbuffer_normal, texel, 0).xy);
  vec3 albedo = srgb_decode(texelFetch(gbuffer_albedo, texel, 0).rgb);
  out_radiance = lambertian_direct(position, normal, albedo);
}
