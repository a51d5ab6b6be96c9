// GTAO (Jimenez et al. 2016, "Practical Realtime Strategies for Accurate
// Indirect Occlusion"), the ambient visibility without the multi-bounce fit
// (docs/deep-sao.md, "Slice estimators"). Included by sao.frag where
// AO_METHOD is DEEPGI_AO_METHOD_GTAO; reads what sao.frag declares and
// ao_slice.glsl, which sao.frag includes first.
//
// Per slice (ao_slice.glsl), each side's horizon is the sample seen highest
// (nearest V) among ao-steps samples out to the AO radius; a sample of either
// layer raises it. No falloff: a point farther than the radius from X is no
// occluder at all, closer it hides everything below it, as the reference's
// rays do within r. A point less than the footprint bias above X's tangent
// plane is taken for X's own surface. The horizons are clamped to the half
// circle around the projected normal, and the slice's visibility is the
// inner integral |n_p| (G(h2) - G(h1)). The slices' sum is divided by the
// same sum with no occluder (|n_p| (cos n + n sin n) per slice), so an open
// surface gives exactly 1 whatever the number of slices; the integral over
// all slice angles is the same with or without the division.

// One layer's sample at pixel `at` (linear depth z, 0 = nothing): raises
// its side's horizon. A function called once per layer, not a loop over the
// layers: llvmpipe runs a loop over the layers as a loop, each select on the
// layer at run time (docs/ao-accuracy.md, "One call per layer in every estimator").
void gtao_sample(AoSlice slice, ivec2 at, float z, float side, vec3 position, vec3 normal, float radius_squared,
                 float footprint_bias, inout float low, inout float high) {
  if (z <= 0.0) return;
  vec3 w = camera_position_at(vec2(at) + 0.5, z, frame.internal_size, frame.camera_ray_scale) - position;
  if (dot(w, w) >= radius_squared || dot(w, normal) <= footprint_bias) return;
  float theta = slice_angle(slice, w);
  if (side > 0.0) high = min(high, theta);
  else low = max(low, theta);
}

// The visibility in [0, 1], raised to `intensity`.
float ao_visibility(ivec2 pixel, float depth, vec3 position, vec3 normal, float radius,
                    float radius_pixels, float bias, float footprint_bias, float intensity,
                    mat2 rotation) {
  float radius_squared = radius * radius;
  float jitter = slice_jitter(pixel);
  float visible = 0.0;
  float open = 0.0;
  for (int s = 0; s < sao.slices; ++s) {
    AoSlice slice = make_slice(s, sao.slices, position, normal, rotation);
    float n = slice.normal_angle;
    float low = n - 0.5 * pi;
    float high = n + 0.5 * pi;
    for (int side_index = 0; side_index < 2; ++side_index) {
      float side = side_index == 0 ? -1.0 : 1.0;
      for (int k = 0; k < sao.steps; ++k) {
        ivec2 at;
        if (!slice_sample(slice, pixel, side, k, jitter, radius_pixels, at)) continue;
        vec2 depths = texelFetch(depth_pyramid, at, 0).rg;
        gtao_sample(slice, at, depths.r, side, position, normal, radius_squared, footprint_bias, low, high);
#if AO_LAYERS > 1
        gtao_sample(slice, at, depths.g, side, position, normal, radius_squared, footprint_bias, low, high);
#endif
      }
    }
    high = max(high, low);
    visible += slice.normal_length * (slice_measure(high, n) - slice_measure(low, n));
    open += slice.normal_length * (slice_measure(n + 0.5 * pi, n) - slice_measure(n - 0.5 * pi, n));
  }
  return open > 0.0 ? pow(clamp(visible / open, 0.0, 1.0), intensity) : 1.0;
}
