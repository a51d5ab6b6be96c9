// The key light as seen from a camera-space point: shared by the direct light
// pass now and by later passes that relight surfaces.
#include "math_constants.glsl"

// The including shader chooses where the shadow maps are bound: it defines
// LIGHTING_SHADOW_MAP_BINDING and LIGHTING_SHADOW_CUBE_BINDING first.
layout(binding = LIGHTING_SHADOW_MAP_BINDING) uniform sampler2DShadow shadow_map;
layout(binding = LIGHTING_SHADOW_CUBE_BINDING) uniform samplerCubeShadow shadow_cube;

// Point light: one lookup (2x2 comparison filtered) in the depth cube. The
// face is the direction's major axis, and its stored depth is that face's
// perspective depth of the major-axis distance.
float point_shadow_visibility(vec3 camera_position, vec3 camera_normal) {
  float distance = length(camera_position - frame.light_vector.xyz);
  vec3 offset_position = camera_position + camera_normal * (frame.shadow_normal_offset * distance);
  // The cube's faces are world aligned; the view matrix is rigid.
  vec3 direction = transpose(mat3(frame.view)) * (offset_position - frame.light_vector.xyz);
  float major = max(abs(direction.x), max(abs(direction.y), abs(direction.z)));
  float near_plane = frame.spot_axis.x, far_plane = frame.spot_axis.y;
  if (major >= far_plane) return 1.0;
  float depth = far_plane / (far_plane - near_plane) -
                far_plane * near_plane / ((far_plane - near_plane) * max(major, near_plane));
  return texture(shadow_cube, vec4(direction, depth));
}

// 3x3 PCF with hardware 2x2 comparison filtering: soft enough to hide texels,
// cheap enough for llvmpipe.
float shadow_visibility(vec3 camera_position, vec3 camera_normal) {
  if (frame.light_kind == DEEPGI_LIGHT_POINT)
    return point_shadow_visibility(camera_position, camera_normal);
  vec3 offset_position = camera_position + camera_normal * frame.shadow_normal_offset;
  vec4 clip = frame.camera_to_light_clip * vec4(offset_position, 1.0);
  if (clip.w <= 0.0) return 0.0;
  vec3 ndc = clip.xyz / clip.w;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z > 1.0) return 1.0;
  vec2 texel = 1.0 / vec2(textureSize(shadow_map, 0));
  float lit = 0.0;
  for (int y = -1; y <= 1; ++y) {
    for (int x = -1; x <= 1; ++x) {
      lit += texture(shadow_map, vec3(uv + vec2(x, y) * texel, ndc.z));
    }
  }
  return lit / 9.0;
}

// Irradiance arriving at a surface facing the light, before the cosine and shadow.
vec3 light_irradiance(vec3 camera_position, out vec3 to_light) {
  if (frame.light_kind == DEEPGI_LIGHT_DIRECTIONAL) {
    to_light = frame.light_vector.xyz;
    return frame.light_radiance.rgb;
  }
  vec3 offset = frame.light_vector.xyz - camera_position;
  float distance_squared = max(dot(offset, offset), 1e-4);
  to_light = offset * inversesqrt(distance_squared);
  float window = 1.0;
  if (frame.light_vector.w > 0.0) {
    // KHR_lights_punctual's range window: 1 - (d / range)^4, clamped.
    float ratio_squared = distance_squared * frame.light_vector.w * frame.light_vector.w;
    window = clamp(1.0 - ratio_squared * ratio_squared, 0.0, 1.0);
  }
  float cone = 1.0;
  if (frame.light_kind == DEEPGI_LIGHT_SPOT) {
    float cos_angle = dot(-to_light, frame.spot_axis.xyz);
    cone = smoothstep(frame.spot_axis.w, frame.light_radiance.w, cos_angle);
  }
  return frame.light_radiance.rgb * (cone * window) / distance_squared;
}

vec3 lambertian_direct(vec3 camera_position, vec3 camera_normal, vec3 albedo) {
  vec3 to_light;
  vec3 irradiance = light_irradiance(camera_position, to_light);
  float cosine = max(dot(camera_normal, to_light), 0.0);
  if (cosine <= 0.0) return vec3(0.0);
  return albedo / pi * irradiance * cosine * shadow_visibility(camera_position, camera_normal);
}
