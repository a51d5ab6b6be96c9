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

// x rounded toward zero to a half-float value, as llvmpipe's store to a
// half-float image rounds (packHalf2x16 rounds to nearest, which moved 1 in 4
// radiance values by one half-float step): the largest finite half past it,
// a denormal half below 2^-14, infinities and NaN as they are.
float half_toward_zero(float x) {
  float magnitude = abs(x);
  if (isnan(x) || isinf(x)) return x;
  float truncated;
  if (magnitude >= 65504.0) truncated = 65504.0;
  else if (magnitude >= 6.103515625e-05) truncated = uintBitsToFloat(floatBitsToUint(magnitude) & 0xffffe000u);
  else truncated = floor(magnitude * 16777216.0) * 5.9604644775390625e-08;  // whole multiples of 2^-24
  return uintBitsToFloat(floatBitsToUint(truncated) | (floatBitsToUint(x) & 0x80000000u));
}

uvec4 pack_prepared(float depth, vec2 encoded_normal, vec3 radiance) {
  return uvec4(floatBitsToUint(depth), packHalf2x16(encoded_normal),
               packHalf2x16(vec2(half_toward_zero(radiance.r), half_toward_zero(radiance.g))),
               packHalf2x16(vec2(half_toward_zero(radiance.b), 0.0)));
}

float prepared_depth(uvec4 texel) { return uintBitsToFloat(texel.x); }
vec2 prepared_encoded_normal(uvec4 texel) { return unpackHalf2x16(texel.y); }
vec3 prepared_radiance(uvec4 texel) { return vec3(unpackHalf2x16(texel.z), unpackHalf2x16(texel.w).x); }
