#pragma once
// CPU evaluation of the two slice estimators of the deep SAO pass, gtao and
// bitmask (docs/deep-sao.md, "Slice estimators"), written from their
// formulas as the oracle the GPU read-backs are compared with per pixel.
// Shared with the shaders rather than derived: the per-pixel rotation hash
// (shaders/pixel_rotation_hash.h, checked on its own in
// pixel_rotation_test.cpp) and the seed of the per-pixel step jitter
// (0x2c1b3c6d). A change to the seed in ao_slice.glsl must be made here too.
#include "sao_reference.hpp"

namespace deepgi::test {

// Ambient visibility per pixel (1 channel, the pyramid's level-0 size) of
// the first frame (the temporal sequence's point 0: no extra angle, no
// extra jitter), for settings.method gtao or bitmask. Reads level 0 of the
// pyramid (both layers' linear depths) and the layer-0 normals.
FloatImage reference_slice_visibility(const SaoInputs& inputs, const AoSettings& settings);

// The closed form the corner test holds both to: the ambient visibility, with
// the reference's falloff f(d) = 1 - d^2 / r^2, of a point on a floor at
// distance d from an unbounded perpendicular wall,
//   V(t) = 1 - ((1 + 2 t^2) acos t - 3 t sqrt(1 - t^2)) / pi,
// t = d / r (1 for t >= 1).
double corner_visibility(double distance, double radius);

}  // namespace deepgi::test
