// The published deep SAO estimator (docs/design.md, section 5.6), kept for
// comparison: 1 - sqrt(pi/N * sum AO(X, Y)) over the spiral taps of
// ao_taps.glsl, each tap testing both depth layers and keeping the larger
// occlusion. Included by sao.frag where AO_METHOD is
// DEEPGI_AO_METHOD_PUBLISHED; reads what sao.frag declares.

// Keeps a tap at the centre from dividing by zero; m^2, far below any v.v a
// tap past the bias can have.
const float obscurance_epsilon = 1.0e-4;

// AO(X, Y) of the published SAO estimator (docs/design.md, section 5.6).
// Negative beyond the radius: the caller clamps once against zero after
// taking the larger of both layers.
float obscurance(vec3 v, vec3 normal, float radius_squared, float bias) {
  float vv = dot(v, v);
  float vn = dot(v, normal);
  return (1.0 - vv / radius_squared) * max((vn - bias) / sqrt(vv + obscurance_epsilon), 0.0);
}

// The visibility in [0, 1], raised to `intensity`.
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
    float occlusion = 0.0;
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
    sum += occlusion;
  }
  return pow(max(0.0, 1.0 - sqrt(pi / float(AO_NUM_TAPS) * sum)), intensity);
}
