// What the two slice estimators share (ao_gtao.glsl, ao_bitmask.glsl;
// docs/deep-sao.md, "Slice estimators"): the slice frame, the samples along
// one slice side, and the slice's cosine-weighted measure. Reads what
// sao.frag declares.
//
// A slice is the plane through the eye that holds the pixel's view ray and
// the screen direction d. Angles theta in it are measured from the view
// vector V (X to the eye), positive toward the screen direction d. With the
// normal projected into the slice, n_p at signed angle n from V, the
// cosine-weighted visibility of the directions theta in [a, b] of the slice
// is |n_p| * (G(b) - G(a)) with
//   G(h) = int_0^h cos(theta - n) |sin(theta)| dtheta
//        = sign(h) / 4 * (-cos(2h - n) + cos(n) + 2h sin(n)),
// the inner integral of Jimenez et al. 2016 (|sin| is the measure of the
// sphere around V). The open half circle [n - pi/2, n + pi/2] gives
// cos(n) + n sin(n).

struct AoSlice {
  vec3 view;        // V, unit, from X toward the eye
  vec3 along;       // unit, in the slice, perpendicular to V, toward +d
  vec2 direction;   // d on screen, unit
  float normal_angle;   // n
  float normal_length;  // |n_p|
  float cos_n;          // cos(n), sin(n)
  float sin_n;
};

float slice_measure(float h, float n) {
  float g = 0.25 * (-cos(2.0 * h - n) + cos(n) + 2.0 * h * sin(n));
  return h < 0.0 ? -g : g;
}

// Slice s of `slices`: d = the pixel's rotation (and this frame's angle)
// applied to angle pi s / slices, so the slices split the half turn evenly.
AoSlice make_slice(int s, int slices, vec3 position, vec3 normal, mat2 rotation) {
  AoSlice slice;
  float angle = pi * float(s) / float(slices);
  slice.direction = rotation * vec2(cos(angle), sin(angle));
  slice.view = normalize(-position);
  vec3 d3 = vec3(slice.direction, 0.0);
  slice.along = normalize(d3 - slice.view * dot(d3, slice.view));
  vec3 axis = cross(slice.view, slice.along);  // the slice plane's normal
  vec3 projected = normal - axis * dot(normal, axis);
  slice.normal_length = length(projected);
  float cos_n = slice.normal_length > 0.0 ? clamp(dot(projected, slice.view) / slice.normal_length, -1.0, 1.0) : 1.0;
  slice.normal_angle = (dot(projected, slice.along) < 0.0 ? -1.0 : 1.0) * acos(cos_n);
  slice.cos_n = cos_n;
  slice.sin_n = sin(slice.normal_angle);
  return slice;
}

// G(theta) for the direction of a vector with components p along and q
// along V in the slice (theta = atan(p, q), given), without a cosine:
// cos(2 theta - n) = cos(2 theta) cos(n) + sin(2 theta) sin(n), and
// cos(2 theta), sin(2 theta) are (q^2 - p^2, 2 p q) / (p^2 + q^2).
float slice_measure_of(AoSlice slice, float p, float q, float theta) {
  float c = ((q * q - p * p) * slice.cos_n + 2.0 * p * q * slice.sin_n) / (p * p + q * q);
  float g = 0.25 * (-c + slice.cos_n + 2.0 * theta * slice.sin_n);
  return theta < 0.0 ? -g : g;
}

// The signed slice angle of the vector w from X.
float slice_angle(AoSlice slice, vec3 w) {
  return atan(dot(w, slice.along), dot(w, slice.view));
}

// Sample k of one slice side (side = +1 along d, -1 against it): the pixel
// it reads, at (k + jitter) / steps of the radius in pixels; false off the
// buffer or on X's own pixel. The jitter is one random fraction per pixel
// plus the second coordinate of this frame's temporal sample, as the march's.
bool slice_sample(AoSlice slice, ivec2 pixel, float side, int k, float jitter, float radius_pixels,
                  out ivec2 at) {
  float t = (float(k) + jitter) / float(sao.steps) * radius_pixels;
  at = ivec2(floor(vec2(pixel) + 0.5 + side * slice.direction * min(t, 65536.0)));
  if (at == pixel) return false;
  ivec2 size = ivec2(frame.internal_size.xy);
  return all(greaterThanEqual(at, ivec2(0))) && all(lessThan(at, size));
}

float slice_jitter(ivec2 pixel) {
  return fract(float(avalanche32(pixel_rotation_hash(uvec2(pixel), uint(frame.rotation_seed)) ^ 0x2c1b3c6du) >> 8u) * (1.0 / 16777216.0) +
               frame.temporal_sample.y);
}
