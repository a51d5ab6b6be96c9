// The thickness-aware spiral estimator of deep SAO (docs/design.md, section
// 5.6; docs/deep-sao.md, "The thick spiral"). Included by sao.frag where
// AO_METHOD is DEEPGI_AO_METHOD_SPIRAL_THICK; reads what sao.frag declares
// (the depth pyramid, which carries the back-face depths for this estimator,
// the generated taps of ao_taps.glsl).
//
// Every stored surface is the front of a solid that reaches back along its
// camera ray to the nearest back face behind it (backface_depth.frag), or
// sao.thickness deep behind an open mesh, as in the march. Tap i of the
// spiral reads, per layer, that solid's segment on the camera ray through the
// tap's source pixel, from its front point F to its back point B. Seen from
// X, the segment occludes directions between the elevations of F and B at the
// tap's azimuth.
//
// The hemisphere is kept as AO_THICK_SECTORS azimuth sectors of the tangent
// plane (2 up to 12 taps, then growing like sqrt(AO_NUM_TAPS):
// ao_thick_sectors.h), each a 32-bit mask over u = sin^2(elevation) in [0, 1]. With
// cos(theta) = sin(elevation) the cosine-weighted measure of a band of
// elevations is, per unit azimuth, (1/2) d(sin^2), so equal steps of u are
// equal shares of the projected solid angle and a bit's share is
// 1 / (32 * AO_THICK_SECTORS): a popcount is an exact cosine weighting.
//
// The taps come in order of growing radius (alpha_i ascends), so the first
// tap to cover a bit is, near enough, the nearest occluder in those
// directions: a bit counts once, with the reference's falloff
// f(d) = 1 - d^2 / r^2 at the tap's distance d (the segment's nearest point
// to X), as the reference's rays count their first hit. Bits no tap covers
// are open. A sector no tap on the buffer fell into is unknown rather than
// open: the estimate is the mean over the sectors seen.

#include "ao_thick_sectors.h"

// A study may fix the count (a define of its own before this include).
#ifndef AO_THICK_SECTORS
#define AO_THICK_SECTORS DEEPGI_AO_THICK_SECTORS_FOR(AO_NUM_TAPS)
#endif

// Bits first to last of a 32-bit mask set, 0 <= first <= last <= 31.
uint bit_range(int first, int last) {
  return (0xffffffffu >> uint(31 - last)) & (0xffffffffu << uint(first));
}

// u = sin^2 of the elevation of v above X's plane raised by threshold, from
// v's height above X's plane; a point below the raised plane is at 0.
float elevation_u(vec3 v, float height_above_plane, float threshold) {
  float height = height_above_plane - threshold;
  return height > 0.0 ? min(height * height / dot(v, v), 1.0) : 0.0;
}

// Where the camera ray `ray` (at unit depth) meets the tap's plane, given by
// its normal and plane_offset = dot(point on it, normal); depth kept within
// a factor 10 of the tap's, so a plane seen edge-on does not run off to
// infinity.
vec3 cell_end(vec3 ray, vec3 plane_normal, float plane_offset, float depth) {
  float along = dot(ray, plane_normal);
  float t = abs(along) > 1.0e-6 ? plane_offset / along : depth;
  return ray * clamp(t, 0.1 * depth, 10.0 * depth);
}

// threshold: points less than this above X's tangent plane are X's own
// surface (sao.frag's footprint threshold); elevations are measured from
// that raised plane.
//
// The cost is the loop body's, per tap and layer (docs/ao-accuracy.md, the
// thick spiral's cost): the camera rays are affine in the pixel position and
// are built once per tap, not per layer, and with two sectors the sector is
// the sign of the azimuth's sine, with no atan.
float spiral_thick_visibility(ivec2 pixel, vec3 position, vec3 normal, float radius,
                              float radius_pixels, float threshold, mat2 rotation) {
  // The sectors turn with the pixel's rotation: a fixed split would line up
  // with the view (towards the camera against away from it) and bias every
  // pixel beside a wall the same way.
  vec3 axis_t = normalize(cross(normal, abs(normal.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0)));
  vec3 axis_b = cross(normal, axis_t);
  vec3 tangent = rotation[0].x * axis_t + rotation[0].y * axis_b;
  vec3 bitangent = cross(normal, tangent);
  float radius_squared = radius * radius;
  float inverse_radius_squared = 1.0 / radius_squared;
#if AO_THICK_SECTORS == 2
  uint mask_lower = 0u, mask_upper = 0u;
#else
  uint masks[AO_THICK_SECTORS];
  for (int k = 0; k < AO_THICK_SECTORS; ++k) masks[k] = 0u;
#endif
  float occlusion = 0.0;
  // Sectors some tap landed in on the buffer: the others (taps off the
  // guard band, towards the camera next to the bottom edge) are unknown,
  // not open, and leave the estimate to the sectors that were seen.
  uint informed = 0u;
  vec2 pixel_centre = vec2(pixel) + 0.5;
  // The camera ray at unit depth through pixel_centre + d is x_ray plus
  // (d * ray_step, 0) (camera_position_at is affine in the pixel position).
  vec3 x_ray = camera_position_at(pixel_centre, 1.0, frame.internal_size, frame.camera_ray_scale);
  vec2 ray_step = 2.0 * frame.internal_size.zw * frame.camera_ray_scale.xy;
  // Half the radial spacing of the taps within one sector, in alpha.
  float cell = 0.5 * float(AO_THICK_SECTORS) / float(AO_NUM_TAPS);
  for (int i = 0; i < AO_NUM_TAPS; ++i) {
    ivec2 texel;
    int level;
    vec2 tap_centre;
    if (!spiral_tap(i, pixel, rotation, radius_pixels, texel, level, tap_centre)) continue;
    // Both layers' front depths (RG) and back faces (BA, linear, 0 = none:
    // depth_pyramid.comp) in one fetch.
    vec4 tap_depths = texelFetch(depth_pyramid, texel, level);
    ivec2 source = ivec2(tap_centre);
    vec2 direction = rotation * AO_TAP_OFFSETS[i] * (radius_pixels / AO_TAP_ALPHAS[i]);
    // The tap stands for its sector's radial cell: its surface, taken as
    // its tangent plane, from alpha - w to alpha + w along its direction.
    vec3 near_ray = x_ray + vec3(ray_step * direction * max(AO_TAP_ALPHAS[i] - cell, 0.0), 0.0);
    vec3 far_ray = x_ray + vec3(ray_step * direction * (AO_TAP_ALPHAS[i] + cell), 0.0);
    vec3 tap_ray = camera_position_at(tap_centre, 1.0, frame.internal_size, frame.camera_ray_scale);
    for (int layer = 0; layer < AO_LAYERS; ++layer) {
      float front = layer == 0 ? tap_depths.r : tap_depths.g;
      if (front <= 0.0) continue;
      float back_face = layer == 0 ? tap_depths.b : tap_depths.a;
      float back = back_face > 0.0 ? max(back_face, front) : front + sao.thickness;
      vec3 front_point = tap_ray * front;
      vec3 f = front_point - position;
      vec3 b = tap_ray * back - position;
      // The front point's azimuth decides the sector.
#if AO_THICK_SECTORS == 2
      // atan(y, x) in (-pi, pi] falls in the upper half exactly where y >= 0.
      bool upper = dot(f, bitangent) >= 0.0;
      informed |= upper ? 2u : 1u;
#else
      // A tap straight above X (f along the normal) has no azimuth; GLSL
      // leaves atan(0, 0) undefined, so it is taken as 0, as in the mirror.
      float along_b = dot(f, bitangent), along_t = dot(f, tangent);
      float azimuth = along_b == 0.0 && along_t == 0.0 ? 0.0 : atan(along_b, along_t);
      int sector = clamp(int(floor((azimuth * (0.5 / pi) + 0.5) * float(AO_THICK_SECTORS))), 0,
                         AO_THICK_SECTORS - 1);
      informed |= 1u << uint(sector);
#endif
      // The segment's nearest point to X gives the distance of the falloff.
      vec3 e = b - f;
      float ee = dot(e, e);
      vec3 nearest = ee > 0.0 ? f + e * clamp(-dot(f, e) / ee, 0.0, 1.0) : f;
      float dd = dot(nearest, nearest);
      float height_f = dot(f, normal), height_b = dot(b, normal);
      // Beyond the radius, or below X's plane: hides nothing.
      if (dd >= radius_squared || (height_f <= threshold && height_b <= threshold)) continue;
      vec3 tap_normal = decode_normal(texelFetch(gbuffer_normal, ivec3(source, layer), 0).xy);
      float plane_offset = dot(front_point, tap_normal);
      vec3 near_end = cell_end(near_ray, tap_normal, plane_offset, front) - position;
      vec3 far_end = cell_end(far_ray, tap_normal, plane_offset, front) - position;
      float u_f = elevation_u(f, height_f, threshold), u_b = elevation_u(b, height_b, threshold);
      float u_near = elevation_u(near_end, dot(near_end, normal), threshold);
      float u_far = elevation_u(far_end, dot(far_end, normal), threshold);
      // Where the tap's plane meets the camera ray through X behind X, the
      // tap's surface runs into X's (a crease): it is taken to continue
      // down to X's plane, and its band to start at the horizon. In front
      // of X it would be a surface invented in front of X (a silhouette).
      // That is plane_offset / toward_x >= 1, without the division.
      float toward_x = dot(position, tap_normal);
      bool crease = toward_x > 0.0 ? plane_offset >= toward_x : toward_x < 0.0 && plane_offset <= toward_x;
      int first = crease ? 0 : min(int(min(min(u_f, u_b), min(u_near, u_far)) * 32.0), 31);
      int last = min(int(max(max(u_f, u_b), max(u_near, u_far)) * 32.0), 31);
      uint bits = bit_range(first, last);
#if AO_THICK_SECTORS == 2
      uint fresh = bits & ~(upper ? mask_upper : mask_lower);
      mask_upper |= upper ? bits : 0u;
      mask_lower |= upper ? 0u : bits;
#else
      uint fresh = bits & ~masks[sector];
      masks[sector] |= bits;
#endif
      occlusion += (1.0 - dd * inverse_radius_squared) * float(bitCount(fresh));
    }
  }
  int seen = bitCount(informed);
  return seen == 0 ? 1.0 : 1.0 - occlusion / float(32 * seen);
}

// The visibility in [0, 1], raised to `intensity`; the footprint threshold
// stands for the bias (spiral_thick_visibility).
float ao_visibility(ivec2 pixel, float depth, vec3 position, vec3 normal, float radius,
                    float radius_pixels, float bias, float footprint_bias, float intensity,
                    mat2 rotation) {
  return pow(spiral_thick_visibility(pixel, position, normal, radius, radius_pixels, footprint_bias, rotation), intensity);
}
