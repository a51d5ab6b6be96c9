// Whether a radiosity sample Y is visible from the gathering point X
// (docs/radiosity.md, "A visibility test per sample"). Included by
// radiosity.frag, whose declarations it reads: the depth pyramid (level 0
// holds both layers' linear depths) and the prepared normals (level 0 holds
// the G-buffer's normals).
//
// Without it the gather counts every surface within the radius that faces X
// and that X faces, also one that other geometry hides from X: on a scene of
// rows of shelves that light is most of what the gather sums. The test
// marches the straight segment from X to Y in `steps` points at
// t = (k + 1/2) / steps and calls Y hidden when one of them lies inside a
// stored surface's solid, the way the AO march treats stored surfaces
// (ao_march.glsl): behind the depth the layer stores at the point's pixel,
// in front of where that surface's solid ends (its back face; behind an open
// mesh, with no back face, `thickness` deep), and behind that surface's
// plane by more than 1 mm per metre of depth, the reconstruction error of a
// stored point and its normal, so that X's and Y's own surfaces never hide
// the segment that leaves them on their front sides.
//
// A segment can cross a part thinner than the steps' spacing between two
// steps, so a point past the solid but within two steps of its front is
// suspect too. It is hidden only where the segment left the camera's sight
// through a surface (the crossing of a thin part), found by halving the
// stretch from the last point the camera saw; where it slipped behind an
// edge into space the camera cannot see, it is not: taking every solid two
// steps deep hid light passing below a beam or behind a column's edge
// (docs/radiosity-studies.md, "Light the allowance hid"). The steps sit at fixed
// fractions of the segment: the rotation of the taps already varies the
// segments from frame to frame, and the CPU mirror can follow the test
// exactly.
#include "radiosity_visibility_constants.h"

layout(binding = 29) uniform sampler2DArray radiosity_backface_depth;

// The pixel of camera-space point c, or (-1, -1) outside the buffer or before
// the near plane.
ivec2 radiosity_visibility_pixel(vec3 c) {
  float z = -c.z;
  if (z <= frame.camera_ray_scale.z) return ivec2(-1);
  vec2 at = (c.xy / (z * frame.camera_ray_scale.xy) * 0.5 + 0.5) * frame.internal_size.xy;
  if (any(lessThan(at, vec2(0.0))) || any(greaterThanEqual(at, frame.internal_size.xy))) return ivec2(-1);
  return ivec2(at);
}

// Whether the camera sees c: before layer 0's depth at its pixel, or nothing
// stored there (nothing known outside the buffer either).
bool radiosity_point_seen(vec3 c) {
  ivec2 p = radiosity_visibility_pixel(c);
  if (p.x < 0) return true;
  float depth = texelFetch(depth_pyramid, p, 0).r;
  return depth <= 0.0 || -c.z < depth;
}

// The segment is seen at a and hidden from the camera at b: whether it goes
// out of sight through the surface layer 0 stores there (a thin part it
// crosses) rather than behind an edge of it (open space the camera cannot
// see). n = DEEPGI_RADIOSITY_CROSSING_HALVINGS halvings bring a and b within
// 1/2^n of their distance; b then lies on or just behind the surface it
// crossed, or far behind the edge it slipped behind.
bool radiosity_segment_enters_surface(vec3 a, vec3 b) {
  for (int i = 0; i < DEEPGI_RADIOSITY_CROSSING_HALVINGS; ++i) {
    vec3 m = 0.5 * (a + b);
    if (radiosity_point_seen(m)) a = m;
    else b = m;
  }
  ivec2 p = radiosity_visibility_pixel(b);
  if (p.x < 0) return false;
  float depth = texelFetch(depth_pyramid, p, 0).r;
  if (depth <= 0.0) return false;
  float z = -b.z;
  vec3 surface = camera_position_at(vec2(p) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
  vec3 surface_normal = decode_normal(texelFetch(prepared_normal, ivec3(p, 0), 0).xy);
  float footprint = 2.0 * frame.camera_ray_scale.y / frame.internal_size.y * z;
  return dot(b - surface, surface_normal) >= -(length(b - a) + 2.0 * footprint + 1.0e-3 * z);
}

bool radiosity_sample_visible(vec3 x, vec3 y, int layers, int steps, float thickness) {
  vec3 v = y - x;
  float step_length = length(v) / float(steps);
  vec3 last_seen = x;  // the last point of the segment the camera sees
  for (int k = 0; k < steps; ++k) {
    vec3 q = x + v * ((float(k) + 0.5) / float(steps));
    // Whether a layer's solid, taken two steps deep, holds q past its stored
    // end: the crossing test reads layer 0 only, so it runs once per step
    // after the layers, not once per layer (on llvmpipe every lane of a
    // batch pays for a call any of them makes).
    bool suspect = false;
    float z = -q.z;
    // A point of the segment between two stored points projects between
    // their pixels, inside the buffer and behind the near plane; the checks
    // guard rounding only.
    if (z <= frame.camera_ray_scale.z) continue;
    vec2 at = (q.xy / (z * frame.camera_ray_scale.xy) * 0.5 + 0.5) * frame.internal_size.xy;
    if (any(lessThan(at, vec2(0.0))) || any(greaterThanEqual(at, frame.internal_size.xy))) continue;
    ivec2 p = ivec2(at);
    vec2 depths = texelFetch(depth_pyramid, p, 0).rg;
    for (int j = 0; j < layers; ++j) {
      float depth = j == 0 ? depths.r : depths.g;
      if (depth <= 0.0 || z <= depth) continue;
      float back_face = texelFetch(radiosity_backface_depth, ivec3(p, j), 0).r;
      float stored_end = back_face > 0.0 ? frame.camera_ray_scale.z / back_face : depth + thickness;
      if (z >= max(stored_end, depth + 2.0 * step_length)) continue;
      vec3 surface = camera_position_at(vec2(p) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
      vec3 surface_normal = decode_normal(texelFetch(prepared_normal, ivec3(p, j), 0).xy);
      if (dot(q - surface, surface_normal) >= -1.0e-3 * z) continue;
      if (z < stored_end) return false;
      suspect = true;
    }
    // Past a stored solid but within two steps of its front: hidden if the
    // segment went out of the camera's sight through a surface (it crossed a
    // part thinner than the steps), not if it slipped behind an edge (the
    // solid taken two steps deep would wrongly hide it).
    if (suspect && radiosity_segment_enters_surface(last_seen, q)) return false;
    if (depths.r <= 0.0 || z < depths.r) last_seen = q;
  }
  return true;
}
