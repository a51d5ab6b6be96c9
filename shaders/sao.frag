#version 450 core
// Deep scalable ambient obscurance (design.md 3, step 4): ambient visibility
// of layer 0 from the spiral taps of the generated ao_taps.glsl, each tap
// testing both depth layers and keeping the larger occlusion.
//
// Define AO_LAYERS 1 to read layer 0 only (for comparison); the default is 2.
// The blur that follows keys on the depth pyramid and the G-buffer normal, so
// the output is visibility alone: in [0, 1] for the published method, signed
// (at most 1) for the solid-angle method, whose consumers clamp it.
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"
#include "pixel_rotation.glsl"
#include "ao_taps.glsl"

#ifndef AO_LAYERS
#define AO_LAYERS 2
#endif

layout(binding = DEEPGI_UNIT_DEPTH_PYRAMID) uniform sampler2D depth_pyramid;
layout(binding = DEEPGI_UNIT_GBUFFER_NORMAL) uniform sampler2DArray gbuffer_normal;

// x: world-space radius r (m), y: bias beta (m), z: intensity (exponent), w: q (px)
layout(location = DEEPGI_UNIFORM_SAO_PARAMETERS) uniform vec4 sao_parameters;
layout(location = DEEPGI_UNIFORM_SAO_MAX_MIP) uniform int max_mip;
// DEEPGI_AO_METHOD_PUBLISHED: 1 - sqrt(pi/N * sum AO(X, Y)), the published
// heuristic. DEEPGI_AO_METHOD_SOLID_ANGLE: the obscurance integral of the
// ray-traced reference, estimated over the visible surface (below).
layout(location = DEEPGI_UNIFORM_SAO_METHOD) uniform int ao_method;

layout(location = 0) out float out_visibility;

// Keeps a tap at the centre from dividing by zero; m^2, far below any v.v a
// tap past the bias can have.
const float obscurance_epsilon = 1.0e-4;
const float pi = 3.14159265;

// One tap's term of the solid-angle estimator. The reference defines
//   O(X) = 1/pi * int_hemisphere f(d) cos(theta) dw,  f(d) = 1 - d^2 / r^2,
// and over the surfaces the G-buffer sees, dw = cos(theta_Y) dA / |v|^2. A
// pixel of side s at unit depth, phi off the optical axis, spans the solid
// angle s^2 cos(phi)^3 from the eye; at linear depth z_Y its surface lies
// z_Y / cos(phi) away, so the patch behind it has the area
//   dA = s^2 cos(phi)^3 (z_Y / cos(phi))^2 / cos(alpha_Y)
//      = (s z_Y)^2 cos(phi) / cos(alpha_Y),
// alpha_Y the angle between its normal and the view ray. Tap i sits at
// radius alpha_i R (R = r / (s z_X) pixels), uniform in radius, so it stands
// for 2 alpha_i pi R^2 / N pixels of area:
//   O ~= 2 r^2 / N * sum_i alpha_i (z_Y / z_X)^2 cos(phi) f cos(theta_X)
//                              cos(theta_Y) / (|v|^2 cos(alpha_Y)).
// cos(theta_Y) is taken as |v.n_Y| / |v|: a seen surface facing away from X
// (the top of a slab above X) stands in for the unseen face of the same thin
// occluder that does face X.
// The bias is a threshold, not a subtraction: a point less than `bias` above
// the tangent plane is taken for X's own surface and ignored, and every other
// point keeps its full cos(theta_X) = v.n / |v|, as in the integral.
// Subtracting the bias shrank the cosine of every real occluder by bias / |v|,
// most where the weight 1 / |v|^2 is largest (next to a crease), and made the
// estimate too bright. A coplanar point needs no margin of its own: its
// cos(theta_X) and cos(theta_Y) are both of the order of the reconstruction
// error, so its term is of the second order. Returns the summand without
// 2 r^2 / N.
float solid_angle_term(vec3 v, vec3 normal, vec3 tap_position, vec3 tap_normal, float radius_squared,
                       float bias, float depth_ratio_squared, float alpha) {
  float vv = dot(v, v);
  if (vv >= radius_squared || vv <= 0.0) return 0.0;
  float vn = dot(v, normal);
  if (vn <= bias) return 0.0;
  float length_v = sqrt(vv);
  float cos_x = vn / length_v;
  float cos_y = abs(dot(v, tap_normal)) / length_v;
  if (cos_y <= 0.0) return 0.0;
  vec3 view_ray = normalize(tap_position);
  float cos_phi = -view_ray.z;
  // A patch seen edge-on stands for unbounded area: clamp its weight.
  float cos_view = max(dot(tap_normal, -view_ray), 0.1);
  return alpha * depth_ratio_squared * cos_phi * (1.0 - vv / radius_squared) * cos_x * cos_y / (vv * cos_view);
}

// AO(X, Y) of design.md 3, step 4. Negative beyond the radius: the caller
// clamps once against zero after taking the larger of both layers.
float obscurance(vec3 v, vec3 normal, float radius_squared, float bias) {
  float vv = dot(v, v);
  float vn = dot(v, normal);
  return (1.0 - vv / radius_squared) * max((vn - bias) / sqrt(vv + obscurance_epsilon), 0.0);
}

// The level-0 pixel whose depth texel `texel` of `level` holds: walks the
// rotated-grid choice of depth_pyramid.comp back down to level 0.
ivec2 source_pixel(ivec2 texel, int level, ivec2 size) {
  for (int l = level; l > 0; --l) {
    ivec2 corner = ivec2((texel.y & 1) ^ 1, (texel.x & 1) ^ 1);
    texel = min(2 * texel + corner, max(size >> (l - 1), ivec2(1)) - 1);
  }
  return texel;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(depth_pyramid, pixel, 0).r;
  if (depth <= 0.0) {  // sky: nothing to occlude
    out_visibility = 1.0;
    return;
  }
  float radius = sao_parameters.x;
  float bias = sao_parameters.y;
  float intensity = sao_parameters.z;
  float q = sao_parameters.w;
  vec3 position = camera_position_at(vec2(pixel) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
  vec3 normal = decode_normal(texelFetch(gbuffer_normal, ivec3(pixel, 0), 0).xy);

  // Pixels per metre at this depth: P11 * height / 2 / depth, P11 = 1 / ray_scale.y.
  float radius_pixels = radius * (0.5 * frame.internal_size.y) / (frame.camera_ray_scale.y * depth);
  float radius_squared = radius * radius;
  mat2 rotation = pixel_rotation(uvec2(pixel));
  // This frame's step of the rotation cycle (frame.cpp), which ao_temporal.frag averages over.
  rotation *= mat2(cos(frame.temporal_angle), sin(frame.temporal_angle), -sin(frame.temporal_angle), cos(frame.temporal_angle));
  ivec2 size = ivec2(frame.internal_size.xy);

  // Solid-angle threshold: the G-buffer samples a surface once per pixel, so
  // a point less than half a pixel footprint at X (metres per pixel at this
  // depth) above the tangent plane cannot be told from X's own surface.
  float footprint_bias = bias + 0.5 * (2.0 * frame.camera_ray_scale.y * depth / frame.internal_size.y);
  float sum = 0.0;
  for (int i = 0; i < AO_NUM_TAPS; ++i) {
    // The clamp keeps the int conversion defined for absurd radii; a tap that
    // far out is off the buffer either way.
    vec2 offset = clamp((rotation * AO_TAP_OFFSETS[i]) * radius_pixels, vec2(-65536.0), vec2(65536.0));
    ivec2 tap = ivec2(floor(vec2(pixel) + 0.5 + offset));
    // Off the guard-banded buffer there is no depth to test: no occlusion.
    if (any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, size))) continue;
    // m_i = clamp(floor(log2(h_i / q)), 0, max_mip), in integers: floor(log2(x))
    // of x >= 1 is the highest set bit of floor(x), exact where log2() may round.
    float steps = min(AO_TAP_ALPHAS[i] * radius_pixels / q, 65536.0);
    int level = steps < 1.0 ? 0 : min(findMSB(uint(steps)), max_mip);
    // Level sizes follow GL's rule max(1, size >> level). Computed rather than
    // asked of textureSize(): llvmpipe (Mesa 22, LLVM 15) answers textureSize
    // with a lod that varies across the SIMD lanes wrongly, and taps vanish.
    ivec2 texel = min(tap >> level, max(size >> level, ivec2(1)) - 1);
    vec2 tap_depths = texelFetch(depth_pyramid, texel, level).rg;
    // Rebuild the tap where its depth came from: the full-resolution pixel
    // the rotated-grid texel copies (depth_pyramid.comp), not the tap's own
    // pixel. A depth put at the wrong pixel is a point off the surface, which
    // shades open floors seen at a grazing angle.
    vec2 tap_centre = vec2(source_pixel(texel, level, size)) + 0.5;
    float occlusion = 0.0;
    if (ao_method == DEEPGI_AO_METHOD_SOLID_ANGLE) {
      ivec2 source = ivec2(tap_centre);
      for (int layer = 0; layer < AO_LAYERS; ++layer) {
        float tap_depth = layer == 0 ? tap_depths.r : tap_depths.g;
        if (tap_depth <= 0.0) continue;
        vec3 y = camera_position_at(tap_centre, tap_depth, frame.internal_size, frame.camera_ray_scale);
        vec3 tap_normal = decode_normal(texelFetch(gbuffer_normal, ivec3(source, layer), 0).xy);
        float ratio = tap_depth / depth;
        occlusion = max(occlusion, solid_angle_term(y - position, normal, y, tap_normal, radius_squared,
                                                    footprint_bias, ratio * ratio, AO_TAP_ALPHAS[i]));
      }
    } else {
      if (tap_depths.r > 0.0) {
        vec3 v = camera_position_at(tap_centre, tap_depths.r, frame.internal_size, frame.camera_ray_scale) - position;
        occlusion = max(occlusion, obscurance(v, normal, radius_squared, bias));
      }
#if AO_LAYERS == 2
      if (tap_depths.g > 0.0) {
        vec3 v = camera_position_at(tap_centre, tap_depths.g, frame.internal_size, frame.camera_ray_scale) - position;
        occlusion = max(occlusion, obscurance(v, normal, radius_squared, bias));
      }
#endif
    }
    sum += occlusion;
  }
  if (ao_method == DEEPGI_AO_METHOD_SOLID_ANGLE) {
    // Signed: the estimate of 1 - O is unbiased, but next to a crease its
    // taps' weights 1 / |v|^2 make it heavy-tailed, and many pixels fall
    // below 0. Clamping each pixel here would cut that tail before the blur
    // and the temporal filter average it out, and bias the result bright, so
    // the value stays signed through them (float targets) and is clamped to
    // [0, 1] where it is consumed (compose, debug views). The exponent shapes
    // the visible range only: pow() is undefined below 0, and a negative
    // value passes unchanged, to be averaged with its neighbours.
    float visibility = 1.0 - 2.0 * radius_squared / float(AO_NUM_TAPS) * sum;
    out_visibility = visibility > 0.0 ? pow(visibility, intensity) : visibility;
  } else {
    out_visibility = pow(max(0.0, 1.0 - sqrt(pi / float(AO_NUM_TAPS) * sum)), intensity);
  }
}
