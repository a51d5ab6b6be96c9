// One texel of the radiosity prepare pass's array (radiosity_prepare.comp):
// everything the gather reads of a sample (tap, layer), so a sample costs one
// fetch where the depth pyramid, a normal texture and a radiance texture cost
// three (docs/radiosity.md, "Cost on llvmpipe"). RGBA32UI:
//   x: the layer's linear depth, the depth pyramid's float bit for bit
//   y: the octahedral normal, packHalf2x16 of the G-buffer's RG16F values
//      (halves already, so packing them is exact)
//   z, w: the outgoing radiance B as halves, (r, g) and (b, 0)
// The halves are the values an RG16F normal and an RGBA16F radiance texture
// held before, so the gather sums exactly what it summed from those.

// The half-float bits of x rounded toward zero, as llvmpipe's store to a
// half-float image rounds (packHalf2x16 rounds to nearest, which moved 1 in
// 4 radiance values by one half-float step), in integer operations: above
// 2^-14 the float's bits shifted and rebiased, below it the whole multiples
// of 2^-24 (a conversion to uint truncates), past the largest finite half
// that half; infinities stay infinite, NaN a NaN.
uint half_bits_toward_zero(float x) {
  uint bits = floatBitsToUint(x);
  uint magnitude = bits & 0x7fffffffu;
  uint normal = min((magnitude >> 13) - 0x1c000u, 0x7bffu);
  uint subnormal = uint(abs(x) * 16777216.0);
  uint half_magnitude = magnitude < 0x38800000u ? subnormal : normal;
  if (magnitude >= 0x7f800000u) half_magnitude = magnitude == 0x7f800000u ? 0x7c00u : 0x7e00u;
  return ((bits >> 16) & 0x8000u) | half_magnitude;
}

uvec4 pack_prepared(float depth, vec2 encoded_normal, vec3 radiance) {
  return uvec4(floatBitsToUint(depth), packHalf2x16(encoded_normal),
               half_bits_toward_zero(radiance.r) | (half_bits_toward_zero(radiance.g) << 16),
               half_bits_toward_zero(radiance.b));
}

float prepared_depth(uvec4 texel) { return uintBitsToFloat(texel.x); }
vec2 prepared_encoded_normal(uvec4 texel) { return unpackHalf2x16(texel.y); }
vec3 prepared_radiance(uvec4 texel) { return vec3(unpackHalf2x16(texel.z), unpackHalf2x16(texel.w).x); }
