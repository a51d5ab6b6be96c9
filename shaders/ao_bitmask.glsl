// The visibility bitmask (Therrien, Levesque, Gilet 2023, "Screen Space
// Indirect Lighting with Visibility Bitmask"), for ambient visibility
// (docs/deep-sao.md, "Slice estimators"). Included by sao.frag where
// AO_METHOD is DEEPGI_AO_METHOD_BITMASK; reads what sao.frag declares and
// ao_slice.glsl, which sao.frag includes first.
//
// The half circle [n - pi/2, n + pi/2] of each slice (ao_slice.glsl) is cut
// into 32 sectors of equal angle, one bit each of a uint. Every sample of
// either layer within the AO radius (and above the footprint bias, as GTAO's)
// is a solid from its front point to the point `sao.thickness` farther along
// its view ray (the constant thickness, ao-thickness), and sets the bits of
// the sectors whose centre lies between the angles of those two points.
// The unset sectors are weighted by their cosine-weighted measure
// |n_p| (G(b) - G(a)) (the GTAO inner integral over the sector), not by
// their count, so that the estimate is of the same ambient visibility as
// the others; as GTAO's, the sum over slices is divided by the open one.

const int bitmask_sectors = 32;

// The sectors whose centres (i + 1/2) / 32 lie in [lo, hi] (fractions of
// the half circle).
uint sector_bits(float lo, float hi) {
  lo = clamp(lo, -1.0, 2.0);
  hi = clamp(hi, -1.0, 2.0);
  int first = max(0, int(ceil(lo * float(bitmask_sectors) - 0.5)));
  int last = min(bitmask_sectors - 1, int(floor(hi * float(bitmask_sectors) - 0.5)));
  if (first > last) return 0u;
  int count = last - first + 1;
  return (count == bitmask_sectors ? 0xffffffffu : ((1u << uint(count)) - 1u)) << uint(first);
}

// One layer's sample at pixel `at` (linear depth z, 0 = nothing): the
// sectors its solid hides, the half circle starting at `start`. A function
// called once per layer, not a loop over the layers: llvmpipe runs a loop
// over the layers as a loop, each select on the layer at run time
// (docs/ao-accuracy.md, "One call per layer in every estimator").
uint bitmask_sample(AoSlice slice, ivec2 at, float z, float start, vec3 position, vec3 normal,
                    float radius_squared, float footprint_bias) {
  if (z <= 0.0) return 0u;
  vec3 front = camera_position_at(vec2(at) + 0.5, z, frame.internal_size, frame.camera_ray_scale);
  vec3 w = front - position;
  if (dot(w, w) >= radius_squared || dot(w, normal) <= footprint_bias) return 0u;
  float a = slice_angle(slice, w);
  float b = slice_angle(slice, w + normalize(front) * sao.thickness);
  return sector_bits((min(a, b) - start) / pi, (max(a, b) - start) / pi);
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
    float start = n - 0.5 * pi;
    uint occupied = 0u;
    for (int side_index = 0; side_index < 2; ++side_index) {
      float side = side_index == 0 ? -1.0 : 1.0;
      for (int k = 0; k < sao.steps; ++k) {
        ivec2 at;
        if (!slice_sample(slice, pixel, side, k, jitter, radius_pixels, at)) continue;
        vec2 depths = texelFetch(depth_pyramid, at, 0).rg;
        occupied |= bitmask_sample(slice, at, depths.r, start, position, normal, radius_squared, footprint_bias);
#if AO_LAYERS > 1
        occupied |= bitmask_sample(slice, at, depths.g, start, position, normal, radius_squared, footprint_bias);
#endif
      }
    }
    // The open measure less that of each run of set bits: a run costs two
    // evaluations of G where summing the 32 sectors would cost 33.
    float slice_open = slice_measure(n + 0.5 * pi, n) - slice_measure(start, n);
    float hidden = 0.0;
    while (occupied != 0u) {
      int first = findLSB(occupied);
      uint above = ~(occupied >> uint(first));  // the run's end is its lowest zero
      int end = above == 0u ? bitmask_sectors : first + findLSB(above);
      hidden += slice_measure(start + pi * float(end) / float(bitmask_sectors), n) -
                slice_measure(start + pi * float(first) / float(bitmask_sectors), n);
      occupied &= end >= bitmask_sectors ? 0u : ~((1u << uint(end)) - 1u);
    }
    visible += slice.normal_length * (slice_open - hidden);
    open += slice.normal_length * slice_open;
  }
  return open > 0.0 ? pow(clamp(visible / open, 0.0, 1.0), intensity) : 1.0;
}
