// The march deep SAO estimator (docs/deep-sao.md, "The march"). Included by
// sao.frag where AO_METHOD is DEEPGI_AO_METHOD_MARCH; reads what sao.frag
// declares (the depth pyramid's level 0, which carries the back-face depths
// for this estimator, and the normal pair).

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
// mesh (no back face) it is `thickness` deep. Behind a part thinner than
// two steps the allowance also fills space the part hides only from the
// camera; the radiosity test's way out (a hit only where the ray left the
// camera's sight through a surface) was measured here and lost far more
// occlusion under slabs, boards and shelves than it freed (docs/deep-sao-studies.md,
// "The two steps' allowance").

// One layer's test of one step: the hit distance along the ray if the
// step's point q (at t, linear depth z) is inside the solid of the surface
// this layer stores at p, else -1. A function called once per layer with a
// constant layer, not a loop over the layers: llvmpipe runs a loop over the
// layers as a loop, each select on the layer at run time
// (docs/ao-accuracy.md, "One call per layer in every estimator").
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
// Not where the stored surface and X's meet at a convex edge: X on or behind
// the stored surface's plane and the stored point on or behind X's (both
// within the same tolerance). The solid fills the whole frustum of the
// stored pixel, which at such an edge (the corner pixel of a pillar's front
// face, X on its side) reaches past the edge, beside X's own face, where
// nothing is; a ray leaving X rises above X's plane, where no object that
// both surfaces bound can be. At a crease (a wall beside a floor) X is in
// front of the wall's plane, so its hits stay (docs/deep-sao.md, "The
// convex-edge test").
float march_layer_hit(float depth, float back_face, vec2 encoded_normal, ivec2 p, vec3 q, float z, float t,
                      float previous, vec3 position, vec3 normal, vec3 direction, float step_length,
                      float bias) {
  if (depth <= 0.0 || z <= depth) return -1.0;
  float solid_end = back_face > 0.0 ? max(back_face, depth + 2.0 * step_length) : depth + sao.thickness;
  if (z >= solid_end) return -1.0;
  vec3 surface = camera_position_at(vec2(p) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
  vec3 surface_normal = decode_normal(encoded_normal);
  float tolerance = bias + 1.0e-3 * z;
  float below = dot(q - surface, surface_normal);
  if (below >= -tolerance) return -1.0;
  if (dot(position - surface, surface_normal) < tolerance && dot(surface - position, normal) < tolerance)
    return -1.0;
  float above = dot(position + direction * previous - surface, surface_normal);
  return above > 0.0 ? previous + (t - previous) * above / (above - below) : t;
}

// The rays through both layers. Rays: Malley's method on the golden-angle
// (Vogel) disk, ray i at radius sqrt((i + 1/2) / R) and angle
// 2 pi frac(i / phi), turned by the pixel's rotation. Steps: evenly spaced
// over r, offset by one random fraction per pixel plus the second coordinate
// of this frame's temporal sample (temporal_sequence.h), so a still camera's
// frames fill the step positions evenly, independently of the angle (the
// first coordinate). Every ray contributes at most 1/R: the value is in
// [0, 1], with no heavy tail for the blur to spread.
float march_visibility(uvec2 pixel, vec3 position, vec3 normal, float radius, float bias,
                       mat2 rotation) {
  // Any tangent frame will do: the rotation randomises the pattern anyway.
  vec3 tangent = normalize(cross(normal, abs(normal.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0)));
  vec3 bitangent = cross(normal, tangent);
  float offset = fract(float(avalanche32(pixel_rotation_hash(pixel, uint(frame.rotation_seed)) ^ 0x68e31da4u) >> 8u) * (1.0 / 16777216.0) + frame.temporal_sample.y);
  float step_length = radius / float(DEEPGI_AO_MARCH_STEPS);
  float occlusion = 0.0;
  for (int i = 0; i < DEEPGI_AO_MARCH_RAYS; ++i) {
    float angle = two_pi * fract(float(i) * 0.618034);
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
      // Both layers' depths and back faces (linear, 0 = none) in one fetch
      // of the pyramid (depth_pyramid.comp), both layers' encoded normals in
      // one of the normal pair (normal_pair.frag): a fetch per layer of each
      // was most of the pass on llvmpipe (docs/ao-accuracy.md).
      vec4 solids = texelFetch(depth_pyramid, p, 0);
      vec4 normals = texelFetch(normal_pair, p, 0);
      hit = march_layer_hit(solids.r, solids.b, normals.xy, p, q, z, t, previous, position, normal, direction,
                            step_length, bias);
#if AO_LAYERS > 1
      if (hit < 0.0)
        hit = march_layer_hit(solids.g, solids.a, normals.zw, p, q, z, t, previous, position, normal, direction,
                              step_length, bias);
#endif
      previous = t;
    }
    if (hit >= 0.0) occlusion += max(0.0, 1.0 - hit * hit / (radius * radius));
  }
  return 1.0 - occlusion / float(DEEPGI_AO_MARCH_RAYS);
}

// The visibility in [0, 1], raised to `intensity`.
float ao_visibility(ivec2 pixel, float depth, vec3 position, vec3 normal, float radius,
                    float radius_pixels, float bias, float footprint_bias, float intensity,
                    mat2 rotation) {
  return pow(march_visibility(uvec2(pixel), position, normal, radius, bias, rotation), intensity);
}
