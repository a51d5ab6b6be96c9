// The per-frame sample of the temporal filters: point k of the R2 sequence
// (Roberts' additive recurrence on the plastic number g = 1.3247...),
//   u_k = frac(k / g),  v_k = frac(k / g^2),
// k the frames since history was invalidated. Every gather that the temporal
// filters average takes this frame's offsets from it: u turns the spiral
// patterns (SAO, radiosity), v shifts the march's step positions, so that
// the frames of a still camera fill the (angle, offset) square evenly and
// never repeat (docs/radiosity.md, "Temporal accumulation"). v also shifts
// the radiosity spiral's tap radii (FrameConstants.temporal_sample.z), which
// the march does not read. A new pass
// that accumulates over frames uses the same point (FrameConstants.temporal_sample).
//
// Written once in the common subset of GLSL and C++, like
// pixel_rotation_hash.h: the includer provides `uint` and
// DEEPGI_SHARED_FUNCTION. The products are taken modulo 2^32 in fixed point
// (the multipliers are 2^32 / g and 2^32 / g^2 rounded), so the fraction is
// exact for every k, where frac(k * 0.7548...) in float would lose the low
// bits of k after a few thousand frames.
#ifndef DEEPGI_TEMPORAL_SEQUENCE_H
#define DEEPGI_TEMPORAL_SEQUENCE_H

DEEPGI_SHARED_FUNCTION uint temporal_sequence_u_fixed(uint k) { return k * 0xc13fa9a9u; }
DEEPGI_SHARED_FUNCTION uint temporal_sequence_v_fixed(uint k) { return k * 0x91e10da6u; }

#endif
