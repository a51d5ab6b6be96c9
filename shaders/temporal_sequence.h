// The per-frame sample of the temporal filters: point k of the
// two-dimensional Sobol sequence, k the frames since history was
// invalidated,
//   u_k = the van der Corput radical inverse of k (its bits reversed),
//   v_k = Sobol's second dimension, whose generator matrix is Pascal's
//         triangle mod 2 (primitive polynomial x + 1),
// each a 32-bit fraction. Every gather that the temporal filters average
// takes this frame's offsets from it: u turns the spiral patterns (SAO,
// radiosity), v shifts the march's step positions, so that the frames of a
// still camera fill the (angle, offset) square evenly and never repeat
// (docs/radiosity.md, "Temporal accumulation"). v also shifts the radiosity
// spiral's tap radii (FrameConstants.temporal_sample.z), which the march does
// not read. A new pass that accumulates over frames uses the same point
// (FrameConstants.temporal_sample).
//
// Why Sobol: any 2^m consecutive frames starting at a multiple of 2^m (so
// frames 0 to 15, 0 to 63, 0 to 255 after a still camera's history starts)
// form a (0, m, 2)-net: every box [i / 2^a, (i + 1) / 2^a) x
// [j / 2^b, (j + 1) / 2^b) with a + b = m holds exactly one point. The
// targets are counted at 16 and 64 frames, and the running mean's cap is 256
// frames, all powers of two; the additive R2 sequence this replaced has no
// such property, and measured slower (docs/radiosity-studies.md, "How fast a
// still camera converges"). Point 0 is (0, 0), so the first frame keeps its taps.
//
// Written once in the common subset of GLSL and C++, like
// pixel_rotation_hash.h: the includer provides `uint` and
// DEEPGI_SHARED_FUNCTION. Only shifts, masks and xors on 32-bit unsigned
// words, so the fractions are exact for every k in both languages.
#ifndef DEEPGI_TEMPORAL_SEQUENCE_H
#define DEEPGI_TEMPORAL_SEQUENCE_H

// Bit i of k becomes bit 31 - i: swaps of halves, bytes, nibbles, pairs,
// bits (GLSL's bitfieldReverse, which C++ lacks).
DEEPGI_SHARED_FUNCTION uint temporal_sequence_u_fixed(uint k) {
  k = (k >> 16u) | (k << 16u);
  k = ((k >> 8u) & 0x00ff00ffu) | ((k & 0x00ff00ffu) << 8u);
  k = ((k >> 4u) & 0x0f0f0f0fu) | ((k & 0x0f0f0f0fu) << 4u);
  k = ((k >> 2u) & 0x33333333u) | ((k & 0x33333333u) << 2u);
  return ((k >> 1u) & 0x55555555u) | ((k & 0x55555555u) << 1u);
}

// The xor of the direction numbers of k's set bits. Direction number i
// (bit i of k) is column i of the Pascal matrix mod 2 placed from the top
// bit down: 1 << 31 for i = 0, and each next one d ^ (d >> 1).
DEEPGI_SHARED_FUNCTION uint temporal_sequence_v_fixed(uint k) {
  uint v = 0u;
  uint direction = 0x80000000u;
  while (k != 0u) {
    if ((k & 1u) != 0u) v ^= direction;
    direction ^= direction >> 1u;
    k >>= 1u;
  }
  return v;
}

#endif
