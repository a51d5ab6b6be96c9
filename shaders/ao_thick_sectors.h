// How many azimuth sectors the thick spiral keeps for a given tap count
// (docs/deep-sao.md, "The thick spiral"), written once for GLSL and C++ so
// the CPU mirror in tests/runtime keeps the shader's sectors.
//
// S(N) = round(sqrt(N)) - 1, at least 2 and at most 8: a sector unions the
// bands of about N / S taps over its whole width of azimuths, which darkens
// the estimate as N grows at a fixed S; too few taps in a sector leave
// occluders between them unseen, which brightens it. Growing S like sqrt(N)
// lets both the sectors and the taps in each grow. Measured on the CPU
// mirror against the ray tracer, S = 2 stays best up to N = 11 (docs).
//
// Integer arithmetic only, so that one expression serves the GLSL and C
// preprocessors' #if (no ?:) and int expressions of both languages:
// (taps + 4096 - t) / 4096 is 1 from taps = t on and 0 below it, for taps in
// [0, 4096). The steps are the N where round(sqrt(N)) - 1 grows:
// round(sqrt(N)) >= k + 1 from N >= (k + 1/2)^2.
#ifndef DEEPGI_AO_THICK_SECTORS_H
#define DEEPGI_AO_THICK_SECTORS_H

#define DEEPGI_AO_THICK_STEP(taps, at) (((taps) + 4096 - (at)) / 4096)
#define DEEPGI_AO_THICK_SECTORS_FOR(taps)                                                    \
  (2 + DEEPGI_AO_THICK_STEP(taps, 13) + DEEPGI_AO_THICK_STEP(taps, 21) +                    \
   DEEPGI_AO_THICK_STEP(taps, 31) + DEEPGI_AO_THICK_STEP(taps, 43) +                        \
   DEEPGI_AO_THICK_STEP(taps, 57) + DEEPGI_AO_THICK_STEP(taps, 73))

#endif
