// GTAO (Jimenez et al. 2016, "Practical Realtime Strategies for Accurate
// Indirect Occlusion"), the ambient visibility without the multi-bounce fit
// (docs/deep-sao.md, "Slice estimators"). Included by sao.frag where
// AO_METHOD is DEEPGI_AO_METHOD_GTAO; reads what sao.frag declares and
// ao_slice.glsl, which sao.frag includes first.
//
// Per slice (ao_slice.glsl), each side's horizon is the sample seen highest
// (nearest V) among ao-steps samples out to the AO radius; a sample of either
// layer raises it. A point less than the footprint bias above X's tangent
// plane is taken for X's own surface. The horizons are clamped to the half
// circle around the projected normal. The samples are taken outward, so
// each rise of the horizon hides directions whose first occluder, along the
// slice, is the sample that raised it: the rise's measure |n_p| (G(new) -
// G(old)) counts with that sample's falloff f(d) = 1 - d^2 / r^2, the
// reference's (as the attenuation of HBAO, Bavoil et al. 2008), so the
// estimate is of the same falloff-weighted visibility as the others. With f
// = 1 the rises sum to the inner integral outside the two horizons, GTAO's
// own estimate. The slices' hidden measures are taken from their open one
// (|n_p| (cos n + n sin n) per slice) and divided by it, so an open surface
// gives exactly 1 whatever the number of slices.

// One layer's sample at pixel `at` (linear depth z, 0 = nothing): moves its
// side's horizon toward V (side -1: `horizon` grows from n - pi/2; side +1:
// it falls from n + pi/2), never past `limit` (side -1: n + pi/2; side +1:
// side -1's horizon), adding the move's measure times the sample's falloff
// to `hidden`. `horizon_measure` and `limit_measure` are G of those angles.
// A function called once per layer, not a loop over the layers: llvmpipe
// runs a loop over the layers as a loop, each select on the layer at run
// time (docs/ao-accuracy.md, "One call per layer in every estimator").
void gtao_sample(AoSlice slice, ivec2 at, float z, float side, vec3 position, vec3 normal,
                 float inverse_radius_squared, float footprint_bias, float limit, float limit_measure,
                 inout float horizon, inout float horizon_measure, inout float hidden) {
  if (z <= 0.0) return;
  vec3 w = camera_position_at(vec2(at) + 0.5, z, frame.internal_size, frame.camera_ray_scale) - position;
  float falloff = 1.0 - dot(w, w) * inverse_radius_squared;
  if (falloff <= 0.0 || dot(w, normal) <= footprint_bias) return;
  float p = dot(w, slice.along), q = dot(w, slice.view);
  float theta = atan(p, q);
  if (side * (horizon - theta) <= 0.0) return;  // below the horizon already
  float m = slice_measure_of(slice, p, q, theta);
  if (side * (theta - limit) <= 0.0) {
    theta = limit;
    m = limit_measure;
  }
  hidden += falloff * abs(m - horizon_measure);
  horizon = theta;
  horizon_measure = m;
}

// The visibility in [0, 1], raised to `intensity`.
float ao_visibility(ivec2 pixel, float depth, vec3 position, vec3 normal, float radius,
                    float radius_pixels, float bias, float footprint_bias, float intensity,
                    mat2 rotation) {
  float inverse_radius_squared = 1.0 / (radius * radius);
  float jitter = slice_jitter(pixel);
  float visible = 0.0;
  float open = 0.0;
  for (int s = 0; s < sao.slices; ++s) {
    AoSlice slice = make_slice(s, sao.slices, position, normal, rotation);
    float n = slice.normal_angle;
    float bottom = n - 0.5 * pi, top = n + 0.5 * pi;
    float bottom_measure = slice_measure(bottom, n), top_measure = slice_measure(top, n);
    float hidden = 0.0;
    // Side -1 first: side +1's horizon stops at side -1's.
    float low = bottom, low_measure = bottom_measure;
    for (int side_index = 0; side_index < 2; ++side_index) {
      float side = side_index == 0 ? -1.0 : 1.0;
      float limit = side > 0.0 ? low : top;
      float limit_measure = side > 0.0 ? low_measure : top_measure;
      float horizon = side > 0.0 ? top : bottom;
      float horizon_measure = side > 0.0 ? top_measure : bottom_measure;
      for (int k = 0; k < sao.steps; ++k) {
        ivec2 at;
        if (!slice_sample(slice, pixel, side, k, jitter, radius_pixels, at)) continue;
        vec2 depths = texelFetch(depth_pyramid, at, 0).rg;
        gtao_sample(slice, at, depths.r, side, position, normal, inverse_radius_squared, footprint_bias, limit,
                    limit_measure, horizon, horizon_measure, hidden);
#if AO_LAYERS > 1
        gtao_sample(slice, at, depths.g, side, position, normal, inverse_radius_squared, footprint_bias, limit,
                    limit_measure, horizon, horizon_measure, hidden);
#endif
      }
      low = horizon;
      low_measure = horizon_measure;
    }
    float slice_open = top_measure - bottom_measure;
    visible += slice.normal_length * (slice_open - hidden);
    open += slice.normal_length * slice_open;
  }
  return open > 0.0 ? pow(clamp(visible / open, 0.0, 1.0), intensity) : 1.0;
}
