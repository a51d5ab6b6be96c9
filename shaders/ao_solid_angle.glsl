// The solid-angle deep SAO estimator (docs/deep-sao.md): the obscurance
// integral of the ray-traced reference, estimated over the visible surface
// from the spiral taps of ao_taps.glsl. Included by sao.frag where AO_METHOD
// is DEEPGI_AO_METHOD_SOLID_ANGLE; reads what sao.frag declares.

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

// One layer's term of one tap (0 where the layer stores nothing there). A
// function called once per layer with a constant layer, not a loop over the
// layers: llvmpipe runs a loop over the layers as a loop, each select on the
// layer at run time (docs/ao-accuracy.md, "One call per layer in every estimator").
float solid_angle_layer(float tap_depth, vec2 encoded_normal, vec2 tap_centre, float depth, vec3 position,
                        vec3 normal, float radius_squared, float footprint_bias, float alpha) {
  if (tap_depth <= 0.0) return 0.0;
  vec3 y = camera_position_at(tap_centre, tap_depth, frame.internal_size, frame.camera_ray_scale);
  vec3 tap_normal = decode_normal(encoded_normal);
  float ratio = tap_depth / depth;
  return max(0.0, solid_angle_term(y - position, normal, y, tap_normal, radius_squared, footprint_bias,
                                   ratio * ratio, alpha));
}

// The visibility, signed (at most 1), raised to `intensity` where positive.
float ao_visibility(ivec2 pixel, float depth, vec3 position, vec3 normal, float radius,
                    float radius_pixels, float bias, float footprint_bias, float intensity,
                    mat2 rotation) {
  float radius_squared = radius * radius;
  float sum = 0.0;
  for (int i = 0; i < AO_NUM_TAPS; ++i) {
    ivec2 texel;
    int level;
    vec2 tap_centre;
    if (!spiral_tap(i, pixel, rotation, radius_pixels, texel, level, tap_centre)) continue;
    vec2 tap_depths = texelFetch(depth_pyramid, texel, level).rg;
    // Both layers' encoded normals at the tap's source pixel in one fetch
    // (normal_pair.frag), where a fetch per layer was a large part of the pass.
    vec4 tap_normals = texelFetch(normal_pair, ivec2(tap_centre), 0);
    float occlusion = solid_angle_layer(tap_depths.r, tap_normals.xy, tap_centre, depth, position, normal,
                                        radius_squared, footprint_bias, AO_TAP_ALPHAS[i]);
#if AO_LAYERS > 1
    occlusion = max(occlusion, solid_angle_layer(tap_depths.g, tap_normals.zw, tap_centre, depth, position,
                                                 normal, radius_squared, footprint_bias, AO_TAP_ALPHAS[i]));
#endif
    sum += occlusion;
  }
  // Signed: the estimate of 1 - O is unbiased, but next to a crease its
  // taps' weights 1 / |v|^2 make it heavy-tailed, and many pixels fall
  // below 0. Clamping each pixel here would cut that tail before the blur
  // and the temporal filter average it out, and bias the result bright, so
  // the value stays signed through them (float targets) and is clamped to
  // [0, 1] where it is consumed (compose, debug views). The exponent shapes
  // the visible range only: pow() is undefined below 0, and a negative
  // value passes unchanged, to be averaged with its neighbours.
  float visibility = 1.0 - 2.0 * radius_squared / float(AO_NUM_TAPS) * sum;
  return visibility > 0.0 ? pow(visibility, intensity) : visibility;
}
