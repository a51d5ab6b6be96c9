#version 450 core
// Deep scalable ambient obscurance (docs/design.md, section 5.6): ambient visibility
// of layer 0 from the spiral taps of the generated ao_taps.glsl, each tap
// testing both depth layers and keeping the larger occlusion.
//
// The march method instead follows DEEPGI_AO_MARCH_RAYS rays through both
// layers (march_visibility below). Define AO_SPIRAL_THICK to build the
// thickness-aware spiral estimator (ao_spiral_thick.glsl) instead of the
// methods chosen by sao.method.
//
// Define AO_LAYERS 1 to read layer 0 only (for comparison); the default is 2.
// The blur that follows keys on the depth pyramid and the G-buffer normal, so
// the output is visibility alone: in [0, 1] for the published and march
// methods, signed (at most 1) for the solid-angle method, whose consumers
// clamp it.
#include "frame_constants.glsl"
#include "pass_parameters.h"
#include "gbuffer_encoding.glsl"
#include "math_constants.glsl"
#include "pixel_rotation.glsl"
#include "rotated_grid.glsl"
#include "ao_taps.glsl"

#ifndef AO_LAYERS
#define AO_LAYERS 2
#endif

// Bindings are this shader's own; sao_pass.cpp binds the same numbers.
layout(binding = 10) uniform sampler2D depth_pyramid;
layout(binding = 0) uniform sampler2DArray gbuffer_normal;
// March and thick spiral only: per layer, the nearest back face at or behind
// the stored surface (reversed Z, 0 = none), where that surface's object ends.
layout(binding = 29) uniform sampler2DArray backface_depth;

// sao.method: DEEPGI_AO_METHOD_PUBLISHED: 1 - sqrt(pi/N * sum AO(X, Y)), the
// published heuristic. DEEPGI_AO_METHOD_SOLID_ANGLE: the obscurance integral
// of the ray-traced reference, estimated over the visible surface (below).
// DEEPGI_AO_METHOD_MARCH: the reference's own rays, marched (below).
// sao.thickness, march only: how deep (m) behind a stored surface with no
// back face behind it (an open mesh: a floor, a wall plane) the scene is
// taken as solid.
layout(std140, binding = DEEPGI_UBO_PASS) uniform SaoBlock {
  SaoParameters sao;
};

layout(location = 0) out float out_visibility;

// Keeps a tap at the centre from dividing by zero; m^2, far below any v.v a
// tap past the bias can have.
const float obscurance_epsilon = 1.0e-4;

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

// AO(X, Y) of the published SAO estimator (docs/design.md, section 5.6).
// Negative beyond the radius: the caller clamps once against zero after
// taking the larger of both layers.
float obscurance(vec3 v, vec3 normal, float radius_squared, float bias) {
  float vv = dot(v, v);
  float vn = dot(v, normal);
  return (1.0 - vv / radius_squared) * max((vn - bias) / sqrt(vv + obscurance_epsilon), 0.0);
}

// The march estimator: the reference's definition, AV = 1 - mean f(d) over
// cosine-weighted rays, f(d) = 1 - d^2 / r^2 for the first hit at d < r,
// estimated with rays marched through the two depth layers. The layers store
// surfaces, not solids, so each stored surface is taken as the front of a
// solid that reaches back along the view ray to the nearest back face behind
// it (backface_depth.frag): the far side of a closed object. That is what
// lets a ray find the occluders no layer stores (board undersides, the unseen
// strip of a wall seen at a grazing angle beside a crease) without darkening
// open surfaces behind thin parts and past convex corners, as a slab of fixed
// depth did (docs/deep-sao.md, "The march"). The solid is at least two steps
// deep, so that a ray crossing a thin part lands inside it; behind an open
// mesh (no back face) it is `thickness` deep.
//
// A step's point q, projected to pixel p, is inside when it lies
//   - behind the depth stored at p: the plane alone is not enough, as the
//     plane of a surface seen edge-on runs along the view ray;
//   - in front of where that surface's solid ends;
//   - behind that surface's plane by more than the bias plus 1 mm per metre
//     of depth, the reconstruction error of a stored point and its normal,
//     so that a ray leaving X's own surface at a grazing angle does not hit it.
// The hit distance is where the last segment crosses that plane.
//
// Rays: Malley's method on the golden-angle (Vogel) disk, ray i at radius
// sqrt((i + 1/2) / R) and angle 2 pi frac(i / phi), turned by the pixel's
// rotation. Steps: evenly spaced over r, offset by one random fraction per
// pixel plus the second coordinate of this frame's temporal sample
// (temporal_sequence.h), so a still camera's frames fill the step positions
// evenly, independently of the angle (the first coordinate).
// Every ray contributes at most 1/R: the value is in [0, 1], with no heavy
// tail for the blur to spread.
float march_visibility(uvec2 pixel, vec3 position, vec3 normal, float radius, float bias,
                       mat2 rotation) {
  // Any tangent frame will do: the rotation randomises the pattern anyway.
  vec3 tangent = normalize(cross(normal, abs(normal.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0)));
  vec3 bitangent = cross(normal, tangent);
  float offset = fract(float(avalanche32(pixel_rotation_hash(pixel) ^ 0x68e31da4u) >> 8u) * (1.0 / 16777216.0) + frame.temporal_sample.y);
  float step_length = radius / float(DEEPGI_AO_MARCH_STEPS);
  float occlusion = 0.0;
  for (int i = 0; i < DEEPGI_AO_MARCH_RAYS; ++i) {
    float angle = 6.2831855 * fract(float(i) * 0.618034);
    vec2 disk = rotation * vec2(cos(angle), sin(angle)) * sqrt((float(i) + 0.5) / float(DEEPGI_AO_MARCH_RAYS));
    vec3 direction = tangent * disk.x + bitangent * disk.y + normal * sqrt(max(0.0, 1.0 - dot(disk, disk)));
    float previous = 0.0;
    float hit = -1.0;
    for (int k = 0; k < DEEPGI_AO_MARCH_STEPS && hit < 0.0; ++k) {
      float t = (float(k) + offset) * step_length;
      vec3 q = position + direction * t;
      float z = -q.z;
      if (z <= frame.camera_ray_scale.z) break;  // in front of the near plane: nothing stored there
      // Off the guard-banded buffer nothing is known: no occluder.
      vec2 at = (q.xy / (z * frame.camera_ray_scale.xy) * 0.5 + 0.5) * frame.internal_size.xy;
      if (any(lessThan(at, vec2(0.0))) || any(greaterThanEqual(at, frame.internal_size.xy))) break;
      ivec2 p = ivec2(at);
      vec2 depths = texelFetch(depth_pyramid, p, 0).rg;
      for (int layer = 0; layer < AO_LAYERS && hit < 0.0; ++layer) {
        float depth = layer == 0 ? depths.r : depths.g;
        if (depth <= 0.0 || z <= depth) continue;
        float back_face = texelFetch(backface_depth, ivec3(p, layer), 0).r;
        float solid_end = back_face > 0.0 ? max(frame.camera_ray_scale.z / back_face, depth + 2.0 * step_length)
                                          : depth + sao.thickness;
        if (z >= solid_end) continue;
        vec3 surface = camera_position_at(vec2(p) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
        vec3 surface_normal = decode_normal(texelFetch(gbuffer_normal, ivec3(p, layer), 0).xy);
        float below = dot(q - surface, surface_normal);
        if (below >= -(bias + 1.0e-3 * z)) continue;
        float above = dot(position + direction * previous - surface, surface_normal);
        hit = above > 0.0 ? previous + (t - previous) * above / (above - below) : t;
      }
      previous = t;
    }
    if (hit >= 0.0) occlusion += max(0.0, 1.0 - hit * hit / (radius * radius));
  }
  return 1.0 - occlusion / float(DEEPGI_AO_MARCH_RAYS);
}

// Where tap i of the generated spiral lands for this pixel: the depth-pyramid
// texel and level it reads, and the centre of the full-resolution pixel that
// texel's depth came from. False where the tap is off the guard-banded buffer
// (no depth there to test: no occlusion).
bool spiral_tap(int i, ivec2 pixel, mat2 rotation, float radius_pixels, out ivec2 texel, out int level,
                out vec2 tap_centre) {
  ivec2 size = ivec2(frame.internal_size.xy);
  // The clamp keeps the int conversion defined for absurd radii; a tap that
  // far out is off the buffer either way.
  vec2 offset = clamp((rotation * AO_TAP_OFFSETS[i]) * radius_pixels, vec2(-65536.0), vec2(65536.0));
  ivec2 tap = ivec2(floor(vec2(pixel) + 0.5 + offset));
  if (any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, size))) return false;
  // m_i = clamp(floor(log2(h_i / q)), 0, max_mip), in integers: floor(log2(x))
  // of x >= 1 is the highest set bit of floor(x), exact where log2() may round.
  float steps = min(AO_TAP_ALPHAS[i] * radius_pixels / sao.q, 65536.0);
  level = steps < 1.0 ? 0 : min(findMSB(uint(steps)), sao.max_mip);
  // Level sizes follow GL's rule max(1, size >> level). Computed rather than
  // asked of textureSize(): llvmpipe (Mesa 22, LLVM 15) answers textureSize
  // with a lod that varies across the SIMD lanes wrongly, and taps vanish.
  texel = min(tap >> level, max(size >> level, ivec2(1)) - 1);
  // Rebuild the tap where its depth came from: the full-resolution pixel
  // the rotated-grid texel copies (depth_pyramid.comp), not the tap's own
  // pixel. A depth put at the wrong pixel is a point off the surface, which
  // shades open floors seen at a grazing angle.
  tap_centre = vec2(rotated_grid_source_pixel(texel, level, size)) + 0.5;
  return true;
}

#ifdef AO_SPIRAL_THICK
#include "ao_spiral_thick.glsl"
#endif

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(depth_pyramid, pixel, 0).r;
  if (depth <= 0.0) {  // sky: nothing to occlude
    out_visibility = 1.0;
    return;
  }
  float radius = sao.radius;
  float bias = sao.bias;
  float intensity = sao.intensity;
  vec3 position = camera_position_at(vec2(pixel) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
  vec3 normal = decode_normal(texelFetch(gbuffer_normal, ivec3(pixel, 0), 0).xy);

  // Pixels per metre at this depth: P11 * height / 2 / depth, P11 = 1 / ray_scale.y.
  float radius_pixels = radius * (0.5 * frame.internal_size.y) / (frame.camera_ray_scale.y * depth);
  float radius_squared = radius * radius;
  mat2 rotation = pixel_rotation(uvec2(pixel));
  // This frame's angle of the temporal sequence (frame.cpp), which ao_temporal.frag averages over.
  rotation *= mat2(cos(frame.temporal_angle), sin(frame.temporal_angle), -sin(frame.temporal_angle), cos(frame.temporal_angle));
  // Solid-angle and thick-spiral threshold: the G-buffer samples a surface
  // once per pixel, so a point less than half a pixel footprint at X (metres
  // per pixel at this depth) above the tangent plane cannot be told from X's
  // own surface.
  float footprint_bias = bias + 0.5 * (2.0 * frame.camera_ray_scale.y * depth / frame.internal_size.y);
#ifdef AO_SPIRAL_THICK
  out_visibility = pow(spiral_thick_visibility(pixel, position, normal, radius, radius_pixels, footprint_bias, rotation), intensity);
  return;
#endif
  if (sao.method == DEEPGI_AO_METHOD_MARCH) {
    out_visibility = pow(march_visibility(uvec2(pixel), position, normal, radius, bias, rotation), intensity);
    return;
  }
  float sum = 0.0;
  for (int i = 0; i < AO_NUM_TAPS; ++i) {
    ivec2 texel;
    int level;
    vec2 tap_centre;
    if (!spiral_tap(i, pixel, rotation, radius_pixels, texel, level, tap_centre)) continue;
    vec2 tap_depths = texelFetch(depth_pyramid, texel, level).rg;
    float occlusion = 0.0;
    if (sao.method == DEEPGI_AO_METHOD_SOLID_ANGLE) {
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
  if (sao.method == DEEPGI_AO_METHOD_SOLID_ANGLE) {
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
