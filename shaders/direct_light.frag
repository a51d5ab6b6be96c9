#version 450 core
// Lambertian direct light of one G-buffer layer (uniform `layer`) into HDR.
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"
// Bindings are this shader's own; direct_light_pass.cpp binds the same numbers.
#define LIGHTING_SHADOW_MAP_BINDING 6
#define LIGHTING_SHADOW_CUBE_BINDING 27
#include "lighting.glsl"

layout(binding = 0) uniform sampler2DArray gbuffer_normal;
layout(binding = 1) uniform sampler2DArray gbuffer_albedo;
layout(binding = 4) uniform sampler2DArray gbuffer_depth;
layout(location = 4) uniform int layer;

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
