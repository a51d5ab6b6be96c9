// The per-pixel rotation hash, written once in the common subset of GLSL and
// C++ so the CPU reference in tests/runtime runs exactly the shader's code.
// The includer provides `uint` (32-bit unsigned) and DEEPGI_SHARED_FUNCTION
// (`inline` in C++, empty in GLSL). Every step is a 32-bit unsigned multiply
// or xor-shift, which both languages define as arithmetic modulo 2^32.
#ifndef DEEPGI_PIXEL_ROTATION_HASH_H
#define DEEPGI_PIXEL_ROTATION_HASH_H

// The 32-bit finaliser of MurmurHash3: a bijection that flips each output bit
// with probability close to 1/2 for any flipped input bit.
DEEPGI_SHARED_FUNCTION uint avalanche32(uint h) {
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

// Distinct x in one row always give distinct hashes (xor with a fixed value,
// then a bijection). The seed (FrameConstants.rotation_seed) picks another
// field of angles: its own avalanche joins the xor, and avalanche32(0) = 0,
// so seed 0 is the shipped field bit for bit. Seed s reads the seed-0 field
// at column x ^ avalanche32(s), far outside any frame for almost every s, so
// every pixel gets an angle unrelated to its seed-0 one.
DEEPGI_SHARED_FUNCTION uint pixel_rotation_hash_xy(uint x, uint y, uint seed) {
  return avalanche32(x ^ avalanche32(y + 0x9e3779b9u) ^ avalanche32(seed));
}

#endif
