// The thickness-aware spiral estimator of deep SAO (docs/design.md, section
// 5.6; docs/deep-sao.md, "The thick spiral"). Included by sao.frag where
// AO_METHOD is DEEPGI_AO_METHOD_SPIRAL_THICK; reads what sao.frag declares
// (the depth pyramid, which carries the back-face depths for this estimator,
// both layers' encoded normals side by side (normal_pair.frag),
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
// are open. A sector no tap's layer-0 surface fell into is unknown rather
// than open: the estimate is the mean over the sectors seen.

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
// v's height above X's plane and its squared length; a point below the
// raised plane is at 0.
float elevation_u(float length_squared, float height_above_plane, float threshold) {
  float height = height_above_plane - threshold;
  return height > 0.0 ? min(height * height / length_squared, 1.0) : 0.0;
}

// One end of a tap's radial cell: u of the point where the camera ray
// x_ray + alpha * step (X's ray moved alpha along the tap's direction, at
// unit depth) meets the tap's plane, given by x_along = dot(x_ray, n),
// step_along = dot(step, n) and plane_offset = dot(point on it, n); depth
// kept within a factor 10 of the tap's (front), so a plane seen edge-on
// does not run off to infinity. The point, less X = x_ray * depth, is
// x_ray * (t - depth) + step * (alpha t): its height and squared length come
// from X's dot products (CellFrame), a few multiplies instead of a vector.
struct CellFrame {
  float depth;        // X's linear depth
  float x_normal;     // dot(x_ray, X's normal)
  float x_x;          // dot(x_ray, x_ray)
  float step_normal;  // dot(step, X's normal)
  float step_x;       // dot(step, x_ray)
  float step_step;    // dot(step, step)
};

float cell_end_u(CellFrame cell, float alpha, float x_along, float step_along, float plane_offset,
                 float front, float threshold) {
  float along = x_along + alpha * step_along;
  float t = abs(along) > 1.0e-6 ? plane_offset / along : front;
  t = clamp(t, 0.1 * front, 10.0 * front);
  float s = t - cell.depth, w = alpha * t;
  float height = s * cell.x_normal + w * cell.step_normal;
  float length_squared = s * (s * cell.x_x + 2.0 * w * cell.step_x) + w * w * cell.step_step;
  return elevation_u(length_squared, height, threshold);
}

// What every tap of one pixel shares: X, its tangent frame (the sectors
// turn with the pixel's rotation), the footprint threshold (points less than
// it above X's tangent plane are X's own surface, sao.frag; elevations are
// measured from that raised plane), the radius and X's camera ray.
struct ThickPixel {
  vec3 position;
  vec3 normal;
  vec3 tangent;
  vec3 bitangent;
  float threshold;
  float radius_squared;
  float inverse_radius_squared;
  vec3 x_ray;  // the camera ray through X at unit depth: X is x_ray * depth
  CellFrame cell_frame;
};

// What both layers of one tap share.
struct ThickTap {
  ivec2 source;          // the full-resolution pixel the tap's depths came from
  vec3 ray;              // the camera ray through it at unit depth
  vec3 step;             // X's camera ray moves by step per unit alpha along the tap's direction
  float near_alpha;      // the tap's radial cell, in alpha
  float far_alpha;
  float nearest_depth;   // depth along ray of its point nearest X
};

// The hemisphere so far: the bitmasks, the sectors seen, the occlusion.
struct ThickState {
#if AO_THICK_SECTORS == 2
  uint mask_lower;
  uint mask_upper;
#else
  uint masks[AO_THICK_SECTORS];
#endif
  // Sectors some tap landed in on the buffer: the others (taps off the
  // guard band, towards the camera next to the bottom edge) are unknown,
  // not open, and leave the estimate to the sectors that were seen.
  uint informed;
  float occlusion;
};

// One layer's solid of one tap, from its front depth to its back face
// (linear, 0 = none: sao.thickness deep), with its surface's encoded normal,
// into the hemisphere; `informs`: layer 0's, whose sector becomes seen. A
// function called once per layer, not a loop over the layers: llvmpipe runs
// a loop over the layers as a loop, each select on the layer at run time.
void add_thick_solid(inout ThickState state, ThickPixel px, ThickTap tap, float front, float back_face,
                     vec2 encoded_normal, bool informs) {
  if (front <= 0.0) return;
  float back = back_face > 0.0 ? max(back_face, front) : front + sao.thickness;
  vec3 front_point = tap.ray * front;
  vec3 f = front_point - px.position;
  vec3 b = tap.ray * back - px.position;
  // The front point's azimuth decides the sector.
#if AO_THICK_SECTORS == 2
  // atan(y, x) in (-pi, pi] falls in the upper half exactly where y >= 0.
  bool upper = dot(f, px.bitangent) >= 0.0;
  // Layer 0 decides which sectors are seen (informs); a layer-1 solid, behind
  // its tap's layer-0 surface, counts only in a sector already seen. Letting
  // it make a sector seen added that sector's open bits to the mean, and two
  // layers came out brighter than one (docs/deep-sao.md, "The thick spiral").
  if (informs) state.informed |= upper ? 2u : 1u;
  else if ((state.informed & (upper ? 2u : 1u)) == 0u) return;
#else
  // A tap straight above X (f along the normal) has no azimuth; GLSL
  // leaves atan(0, 0) undefined, so it is taken as 0, as in the mirror.
  float along_b = dot(f, px.bitangent), along_t = dot(f, px.tangent);
  float azimuth = along_b == 0.0 && along_t == 0.0 ? 0.0 : atan(along_b, along_t);
  int sector = clamp(int(floor((azimuth * (0.5 / pi) + 0.5) * float(AO_THICK_SECTORS))), 0,
                     AO_THICK_SECTORS - 1);
  if (informs) state.informed |= 1u << uint(sector);
  else if ((state.informed & (1u << uint(sector))) == 0u) return;
#endif
  // The segment's nearest point to X gives the distance of the falloff.
  vec3 nearest = tap.ray * clamp(tap.nearest_depth, front, back) - px.position;
  float dd = dot(nearest, nearest);
  float height_f = dot(f, px.normal), height_b = dot(b, px.normal);
  // Beyond the radius, or below X's plane: hides nothing.
  if (dd >= px.radius_squared || (height_f <= px.threshold && height_b <= px.threshold)) return;
  vec3 tap_normal = decode_normal(encoded_normal);
  float plane_offset = dot(front_point, tap_normal);
  float x_along = dot(px.x_ray, tap_normal), step_along = dot(tap.step, tap_normal);
  float u_f = elevation_u(dot(f, f), height_f, px.threshold);
  float u_b = elevation_u(dot(b, b), height_b, px.threshold);
  float u_near = cell_end_u(px.cell_frame, tap.near_alpha, x_along, step_along, plane_offset, front, px.threshold);
  float u_far = cell_end_u(px.cell_frame, tap.far_alpha, x_along, step_along, plane_offset, front, px.threshold);
  // Where the tap's plane meets the camera ray through X behind X, the
  // tap's surface runs into X's (a crease): it is taken to continue
  // down to X's plane, and its band to start at the horizon. In front
  // of X it would be a surface invented in front of X (a silhouette).
  // That is plane_offset / toward_x >= 1, without the division.
  float toward_x = dot(px.position, tap_normal);
  bool crease = toward_x > 0.0 ? plane_offset >= toward_x : toward_x < 0.0 && plane_offset <= toward_x;
  int first = crease ? 0 : min(int(min(min(u_f, u_b), min(u_near, u_far)) * 32.0), 31);
  int last = min(int(max(max(u_f, u_b), max(u_near, u_far)) * 32.0), 31);
  uint bits = bit_range(first, last);
#if AO_THICK_SECTORS == 2
  uint fresh = bits & ~(upper ? state.mask_upper : state.mask_lower);
  state.mask_upper |= upper ? bits : 0u;
  state.mask_lower |= upper ? 0u : bits;
#else
  uint fresh = bits & ~state.masks[sector];
  state.masks[sector] |= bits;
#endif
  state.occlusion += (1.0 - dd * px.inverse_radius_squared) * float(bitCount(fresh));
}

// One layer's stored point on the camera ray through the overhang probe q (at
// linear depth z, the ray at unit depth q / z): a candidate when it hides q
// from the camera, lies at least r / 8 above X's plane and within r of X.
bool overhang_layer(ThickPixel px, float front, float z, vec3 ray, float floor_height, out float dd,
                    out float height) {
  vec3 s = ray * front - px.position;
  height = dot(s, px.normal);
  dd = dot(s, s);
  return front > 0.0 && front < z && height >= floor_height && dd < px.radius_squared;
}

// One overhang probe `up` radii above X along its normal: true where a stored
// surface of either layer hides it and hangs over X, with that point's
// squared distance and height. Hanging over X: the point's elevation is at
// least 45 degrees (u >= 1/2); lower points hid the probe beside small
// occluders (a block's edge on cornell's floor) and closed the hemisphere
// above them where the truth sees it open.
bool overhang_probe(ThickPixel px, float radius, float up, out float dd, out float height) {
  vec3 q = px.position + up * radius * px.normal;
  float z = -q.z;
  vec2 at = (q.xy / (z * frame.camera_ray_scale.xy) + 1.0) * 0.5 * frame.internal_size.xy;
  if (z <= 0.0 || any(lessThan(at, vec2(0.0))) || any(greaterThanEqual(at, frame.internal_size.xy))) return false;
  vec2 fronts = texelFetch(depth_pyramid, ivec2(at), 0).rg;
  float floor_height = 0.125 * radius;
  bool hit = overhang_layer(px, fronts.r, z, q / z, floor_height, dd, height);
#if AO_LAYERS > 1
  if (!hit) hit = overhang_layer(px, fronts.g, z, q / z, floor_height, dd, height);
#endif
  return hit && elevation_u(dd, height, px.threshold) >= 0.5;
}

// The overhang test, after the taps and with no work per tap: the taps that
// land on a surface over X (a slab, a shelf board) lie in a few screen
// directions and their bands need not reach the zenith (docs/deep-sao-studies.md,
// "Where its bias sits"). A probe r / 4 above X, then (where nothing hangs
// over that one) a probe r / 2 above X: the low probe finds boards close
// over a floor, which the high one passes over; the high one finds slabs
// whose edge the low probe's ray passes beneath. Where one finds a surface
// over X, every seen sector's bits from that point's elevation to the
// zenith count, with its falloff, where no tap took them. One or two
// fetches and no loop: a probe per sector, and per-tap candidates before
// it, cost more (docs/deep-sao-studies.md, "Where its bias sits", the
// overhang probe).
void add_overhang(inout ThickState state, ThickPixel px, float radius) {
  float dd, height;
  if (!overhang_probe(px, radius, 0.25, dd, height) && !overhang_probe(px, radius, 0.5, dd, height)) return;
  float u = elevation_u(dd, height, px.threshold);
  uint bits = bit_range(min(int(u * 32.0), 31), 31);
#if AO_THICK_SECTORS == 2
  int fresh = ((state.informed & 1u) != 0u ? bitCount(bits & ~state.mask_lower) : 0) +
              ((state.informed & 2u) != 0u ? bitCount(bits & ~state.mask_upper) : 0);
#else
  int fresh = 0;
  for (int k = 0; k < AO_THICK_SECTORS; ++k)
    fresh += (state.informed & (1u << uint(k))) != 0u ? bitCount(bits & ~state.masks[k]) : 0;
#endif
  state.occlusion += (1.0 - dd * px.inverse_radius_squared) * float(fresh);
}

// The cost is add_thick_solid's, per tap and layer (docs/ao-accuracy.md, the
// thick spiral's cost): the camera rays are affine in the pixel position and
// are built once per tap, not per layer; the cell ends are scalar sums of
// dot products taken once per pixel or tap; the nearest point of each solid
// is a clamp of one depth per tap; one fetch gives both layers' normals (the
// G-buffer's two layers, one fetch each, were more than a third of the pass);
// with two sectors the sector is the sign of the azimuth's sine, with no atan.
float spiral_thick_visibility(ivec2 pixel, vec3 position, vec3 normal, float radius,
                              float radius_pixels, float threshold, mat2 rotation) {
  ThickPixel px;
  px.position = position;
  px.normal = normal;
  // The sectors turn with the pixel's rotation: a fixed split would line up
  // with the view (towards the camera against away from it) and bias every
  // pixel beside a wall the same way.
  vec3 axis_t = normalize(cross(normal, abs(normal.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0)));
  vec3 axis_b = cross(normal, axis_t);
  px.tangent = rotation[0].x * axis_t + rotation[0].y * axis_b;
  px.bitangent = cross(normal, px.tangent);
  px.threshold = threshold;
  px.radius_squared = radius * radius;
  px.inverse_radius_squared = 1.0 / px.radius_squared;
  // The camera ray at unit depth through pixel_centre + d is x_ray plus
  // (d * ray_step, 0) (camera_position_at is affine in the pixel position);
  // X itself is x_ray * depth.
  vec2 pixel_centre = vec2(pixel) + 0.5;
  px.x_ray = camera_position_at(pixel_centre, 1.0, frame.internal_size, frame.camera_ray_scale);
  vec2 ray_step = 2.0 * frame.internal_size.zw * frame.camera_ray_scale.xy;
  px.cell_frame.depth = -position.z;
  px.cell_frame.x_normal = dot(px.x_ray, normal);
  px.cell_frame.x_x = dot(px.x_ray, px.x_ray);
  ThickState state;
#if AO_THICK_SECTORS == 2
  state.mask_lower = 0u;
  state.mask_upper = 0u;
#else
  for (int k = 0; k < AO_THICK_SECTORS; ++k) state.masks[k] = 0u;
#endif
  state.informed = 0u;
  state.occlusion = 0.0;
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
    ThickTap tap;
    tap.source = ivec2(tap_centre);
    // The tap stands for its sector's radial cell: its surface, taken as
    // its tangent plane, from alpha - w to alpha + w along its direction
    // (pixels per unit alpha).
    vec2 direction = rotation * (AO_TAP_OFFSETS[i] / AO_TAP_ALPHAS[i]) * radius_pixels;
    tap.step = vec3(ray_step * direction, 0.0);
    tap.near_alpha = max(AO_TAP_ALPHAS[i] - cell, 0.0);
    tap.far_alpha = AO_TAP_ALPHAS[i] + cell;
    px.cell_frame.step_normal = dot(tap.step, normal);
    px.cell_frame.step_x = dot(tap.step, px.x_ray);
    px.cell_frame.step_step = dot(tap.step, tap.step);
    tap.ray = camera_position_at(tap_centre, 1.0, frame.internal_size, frame.camera_ray_scale);
    // Each layer's solid is nearest X at the depth along the tap's ray
    // nearest X, clamped to the solid's segment.
    tap.nearest_depth = dot(tap.ray, position) / dot(tap.ray, tap.ray);
    // Both layers' encoded normals at the tap's source pixel in one fetch
    // (normal_pair.frag copies them from the G-buffer's two layers).
    vec4 tap_normals = texelFetch(normal_pair, tap.source, 0);
    add_thick_solid(state, px, tap, tap_depths.r, tap_depths.b, tap_normals.xy, true);
#if AO_LAYERS > 1
    add_thick_solid(state, px, tap, tap_depths.g, tap_depths.a, tap_normals.zw, false);
#endif
  }
  add_overhang(state, px, radius);
  int seen = bitCount(state.informed);
  return seen == 0 ? 1.0 : 1.0 - state.occlusion / float(32 * seen);
}

// The visibility in [0, 1], raised to `intensity`; the footprint threshold
// stands for the bias (spiral_thick_visibility).
float ao_visibility(ivec2 pixel, float depth, vec3 position, vec3 normal, float radius,
                    float radius_pixels, float bias, float footprint_bias, float intensity,
                    mat2 rotation) {
  return pow(spiral_thick_visibility(pixel, position, normal, radius, radius_pixels, footprint_bias, rotation), intensity);
}
