#version 450 core
// Deep radiosity gather (design.md 3, step 6) for one G-buffer layer (uniform
// `layer`): irradiance E at X from the taps of the generated
// radiosity_taps.glsl, each tap reading both depth layers.
//
//   E(X) = 2*pi/M * sum over used samples of min(B(Y) * (w.n_X), clamp)
//   w = (Y - X) / |Y - X|
//
// A sample (tap i, layer j) is used when Y lies within the world-space radius,
// X faces it (w.n_X > 0) and it faces X (-w.n_Y > 0); M counts the used
// samples and the confidence is M / (taps * layers). B(Y) is the outgoing
// radiance the gather reads at Y: the lit radiance of the direct light pass,
// plus, for bounces, rho_prop times last frame's indirect radiance
// albedo/pi * E, both scaled by boost(rho_Y), plus emissive (layer 0 only:
// the G-buffer stores emissive for layer 0), so emitters light the scene.
// Taps read level 0 of the G-buffer (no radiance MIP levels yet).
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"
#include "pixel_rotation.glsl"
#include "radiosity_taps.glsl"

layout(binding = DEEPGI_UNIT_GBUFFER_NORMAL) uniform sampler2DArray gbuffer_normal;
layout(binding = DEEPGI_UNIT_GBUFFER_ALBEDO) uniform sampler2DArray gbuffer_albedo;
layout(binding = DEEPGI_UNIT_GBUFFER_EMISSIVE) uniform sampler2DArray gbuffer_emissive;
layout(binding = DEEPGI_UNIT_GBUFFER_DEPTH) uniform sampler2DArray gbuffer_depth;
layout(binding = DEEPGI_UNIT_DIRECT_LIGHT) uniform sampler2DArray direct_light;
// Last frame's E (rgb) per layer, read at this frame's pixel (bounces): exact
// for a static camera, off by the motion otherwise.
layout(binding = DEEPGI_UNIT_RADIOSITY_PREVIOUS_LAYER0) uniform sampler2D previous_irradiance0;
layout(binding = DEEPGI_UNIT_RADIOSITY_PREVIOUS_LAYER1) uniform sampler2D previous_irradiance1;

layout(location = DEEPGI_UNIFORM_LAYER) uniform int layer;
// x: world-space radius (m), y: boost amount in [0, 1] (0: boost = 1, energy
// conserving), z: per-sample contribution clamp, w: rho_prop in [0, 1]
layout(location = DEEPGI_UNIFORM_RADIOSITY_PARAMETERS) uniform vec4 radiosity_parameters;
layout(location = DEEPGI_UNIFORM_RADIOSITY_LAYERS) uniform int gather_layers;  // 1 or 2
// Added to every pixel's rotation, different each frame (golden-ratio steps),
// so the temporal filter averages different patterns instead of one.
layout(location = DEEPGI_UNIFORM_RADIOSITY_ANGLE) uniform float frame_angle;

layout(location = 0) out vec4 out_irradiance;  // rgb: E, a: confidence

const float two_pi = 6.2831853;
const float inv_pi = 0.31830989;

// (max_c rho - min_c rho) / max_c rho blended with 1 by `amount`.
float boost(vec3 rho, float amount) {
  float high = max(rho.r, max(rho.g, rho.b));
  float low = min(rho.r, min(rho.g, rho.b));
  float saturation = high > 0.0 ? (high - low) / high : 0.0;
  return mix(1.0, saturation, amount);
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float stored = texelFetch(gbuffer_depth, ivec3(pixel, layer), 0).r;
  if (stored <= 0.0) {
    out_irradiance = vec4(0.0);
    return;
  }
  float radius = radiosity_parameters.x;
  float boost_amount = radiosity_parameters.y;
  float tap_clamp = radiosity_parameters.z;
  float rho_prop = radiosity_parameters.w;
  float depth = frame.camera_ray_scale.z / stored;
  vec3 position = camera_position_at(vec2(pixel) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
  vec3 normal = decode_normal(texelFetch(gbuffer_normal, ivec3(pixel, layer), 0).xy);
  float radius_pixels = radius * (0.5 * frame.internal_size.y) / (frame.camera_ray_scale.y * depth);
  float radius_squared = radius * radius;
  float phi = pixel_rotation_angle(uvec2(pixel)) + frame_angle;
  mat2 rotation = mat2(cos(phi), sin(phi), -sin(phi), cos(phi));
  ivec2 size = ivec2(frame.internal_size.xy);

  vec3 sum = vec3(0.0);
  int used = 0;
  for (int i = 0; i < RADIOSITY_NUM_TAPS; ++i) {
    vec2 offset = clamp((rotation * RADIOSITY_TAP_OFFSETS[i]) * radius_pixels, vec2(-65536.0), vec2(65536.0));
    ivec2 tap = ivec2(floor(vec2(pixel) + 0.5 + offset));
    if (any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, size))) continue;
    for (int j = 0; j < gather_layers; ++j) {
      ivec3 texel = ivec3(tap, j);
      float tap_stored = texelFetch(gbuffer_depth, texel, 0).r;
      if (tap_stored <= 0.0) continue;
      vec3 y = camera_position_at(vec2(tap) + 0.5, frame.camera_ray_scale.z / tap_stored, frame.internal_size,
                                  frame.camera_ray_scale);
      vec3 v = y - position;
      float vv = dot(v, v);
      if (vv >= radius_squared || vv <= 0.0) continue;
      vec3 w = v * inversesqrt(vv);
      float cos_x = dot(w, normal);
      vec3 tap_normal = decode_normal(texelFetch(gbuffer_normal, texel, 0).xy);
      float cos_y = -dot(w, tap_normal);
      if (cos_x <= 0.0 || cos_y <= 0.0) continue;
      vec3 rho = srgb_decode(texelFetch(gbuffer_albedo, texel, 0).rgb);
      vec3 reflected = texelFetch(direct_light, texel, 0).rgb +
                       rho_prop * inv_pi * rho * (j == 0 ? texelFetch(previous_irradiance0, tap, 0).rgb : texelFetch(previous_irradiance1, tap, 0).rgb);
      vec3 radiance = reflected * boost(rho, boost_amount);
      if (j == 0) radiance += texelFetch(gbuffer_emissive, texel, 0).rgb;
      sum += min(radiance * cos_x, vec3(tap_clamp));
      ++used;
    }
  }
  float samples = float(RADIOSITY_NUM_TAPS * gather_layers);
  vec3 irradiance = used > 0 ? sum * (two_pi / float(used)) : vec3(0.0);
  out_irradiance = vec4(irradiance, float(used) / samples);
}
