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
// The samples are taken outward, so a sector's first setter stands for its
// first occluder: the bits a sample sets first count with its falloff f(d)
// = 1 - d^2 / r^2 at its front point, the reference's, and with their
// cosine-weighted measure |n_p| (G(b) - G(a)) (the GTAO inner integral over
// the sector), not their count, so that the estimate is of the same
// falloff-weighted ambient visibility as the others; as GTAO's, the slices'
// hidden measures are taken from their open one and divided by it.

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

// The measure |n_p| (G(b) - G(a)) / |n_p| of the sectors set in `bits`, the
// half circle starting at `start`: a run of set bits costs two evaluations
// of G where summing its sectors one by one would cost one more per sector.
float sectors_measure(uint bits, float start, float n) {
  float sum = 0.0;
  while (bits != 0u) {
    int first = findLSB(bits);
    uint above = ~(bits >> uint(first));  // the run's end is its lowest zero
    int end = above == 0u ? bitmask_sectors : first + findLSB(above);
    sum += slice_measure(start + pi * float(end) / float(bitmask_sectors), n) -
           slice_measure(start + pi * float(first) / float(bitmask_sectors), n);
    bits &= end >= bitmask_sectors ? 0u : ~((1u << uint(end)) - 1u);
  }
  return sum;
}

// One layer's sample at pixel `at` (linear depth z, 0 = nothing): sets the
// sectors its solid hides, the half circle starting at `start`, and adds the
// measure of those it sets first, times its falloff, to `hidden`. A function
// called once per layer, not a loop over the layers: llvmpipe runs a loop
// over the layers as a loop, each select on the layer at run time
// (docs/ao-accuracy.md, "One call per layer in every estimator").
void bitmask_sample(AoSlice slice, ivec2 at, float z, float start, vec3 position, vec3 normal,
                    float inverse_radius_squared, float footprint_bias, inout uint occupied,
                    inout float hidden) {
  if (z <= 0.0) return;
  vec3 front = camera_position_at(vec2(at) + 0.5, z, frame.internal_size, frame.camera_ray_scale);
  vec3 w = front - position;
  float falloff = 1.0 - dot(w, w) * inverse_radius_squared;
  if (falloff <= 0.0 || dot(w, normal) <= footprint_bias) return;
  float a = slice_angle(slice, w);
  float b = slice_angle(slice, w + normalize(front) * sao.thickness);
  uint fresh = sector_bits((min(a, b) - start) / pi, (max(a, b) - start) / pi) & ~occupied;
  if (fresh == 0u) return;
  occupied |= fresh;
  hidden += falloff * sectors_measure(fresh, start, slice.normal_angle);
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
    float start = n - 0.5 * pi;
    uint occupied = 0u;
    float hidden = 0.0;
    for (int side_index = 0; side_index < 2; ++side_index) {
      float side = side_index == 0 ? -1.0 : 1.0;
      for (int k = 0; k < sao.steps; ++k) {
        ivec2 at;
        if (!slice_sample(slice, pixel, side, k, jitter, radius_pixels, at)) continue;
        vec2 depths = texelFetch(depth_pyramid, at, 0).rg;
        bitmask_sample(slice, at, depths.r, start, position, normal, inverse_radius_squared, footprint_bias, occupied,
                       hidden);
#if AO_LAYERS > 1
        bitmask_sample(slice, at, depths.g, start, position, normal, inverse_radius_squared, footprint_bias, occupied,
                       hidden);
#endif
      }
    }
    float slice_open = slice_measure(n + 0.5 * pi, n) - slice_measure(start, n);
    visible += slice.normal_length * (slice_open - hidden);
    open += slice.normal_length * slice_open;
  }
  return open > 0.0 ? pow(clamp(visible / open, 0.0, 1.0), intensity) : 1.0;
}
