// Per-pixel rotation phi of a gather pattern (docs/design.md, section 1), shared by the
// passes that rotate a spiral and by the CPU reference in tests/runtime.
//
// Why this hash: the classic SAO rotation (3x ^ y + x*y) * 10 multiplies the
// coordinates, so its angle pattern follows the hyperbolas x*y = const and
// overflows 32-bit ints near 4K; fract(sin(dot(p, k))) loses its low bits
// once the argument grows past float precision. Here every step is a 32-bit
// unsigned multiply or xor-shift, which GLSL and C++ both define as
// arithmetic modulo 2^32, so the result is the same for every coordinate the
// renderer accepts (up to 16384) and the same on the CPU.

#include "math_constants.glsl"
#define DEEPGI_SHARED_FUNCTION
#include "pixel_rotation_hash.h"

// seed: FrameConstants.rotation_seed (0: the shipped field); the passes pass
// it explicitly so this file needs no frame block.
uint pixel_rotation_hash(uvec2 pixel, uint seed) { return pixel_rotation_hash_xy(pixel.x, pixel.y, seed); }

// phi in [0, 2*pi), from the top 24 bits so the conversion to float is exact.
float pixel_rotation_angle(uvec2 pixel, uint seed) {
  return float(pixel_rotation_hash(pixel, seed) >> 8u) * (1.0 / 16777216.0) * two_pi;
}

// One 2x2 matrix per pixel; each tap's offset is rotated by it instead of
// evaluating cos and sin per tap.
mat2 pixel_rotation(uvec2 pixel, uint seed) {
  float phi = pixel_rotation_angle(pixel, seed);
  float c = cos(phi);
  float s = sin(phi);
  return mat2(c, s, -s, c);
}
