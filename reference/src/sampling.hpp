#pragma once
// The reference's sampling: per-pixel random streams, scrambled Sobol points
// and the geometry every ray starts from (a tangent frame, an offset off the
// surface). Shared by the visibility and irradiance estimators and the
// driver; inline so that the estimators' inner loops keep them inlined.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace deepgi::reference_sampling {

inline constexpr double pi = 3.14159265358979323846;

// SplitMix64: small, fast, and good enough for per-pixel streams of keys.
struct Random {
    std::uint64_t state;
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
};

inline std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t index) {
    Random mix{seed ^ (index * 0xD1B54A32D192ED03ull)};
    mix.next();
    return mix.next();
}

// Randomised quasi-Monte Carlo points for both estimators.
//
// The first two dimensions of Sobol's sequence, in 32-bit fixed point: the
// index with its bits reversed (van der Corput), and the index through
// Pascal's matrix mod 2. Every aligned run of 2^m points is a (0, m, 2)-net:
// each of the 2^m boxes 2^-a wide and 2^-(m-a) high holds exactly one point,
// and a run of 16 k points is k such nets of 16, so the points stay evenly
// spread whenever the estimator stops.
inline std::uint32_t reverse_bits(std::uint32_t x) {
    x = (x << 16) | (x >> 16);
    x = ((x & 0x00FF00FFu) << 8) | ((x >> 8) & 0x00FF00FFu);
    x = ((x & 0x0F0F0F0Fu) << 4) | ((x >> 4) & 0x0F0F0F0Fu);
    x = ((x & 0x33333333u) << 2) | ((x >> 2) & 0x33333333u);
    return ((x & 0x55555555u) << 1) | ((x >> 1) & 0x55555555u);
}

inline std::uint32_t sobol_y(std::uint32_t index) {
    std::uint32_t bits = 0;
    for (std::uint32_t column = 1u << 31; index != 0; index >>= 1, column ^= column >> 1)
        if (index & 1u) bits ^= column;
    return bits;
}

// A random nested scramble of one coordinate, applied to its bits reversed
// (bit 0 the first binary digit). Each step changes bit k by a function of
// bits 0 .. k-1 only: adding carries upwards, and a product with an even
// factor has bit k made of the bits below k. So digit k of the coordinate
// flips or not by the digits before it, which permutes the two halves of
// every dyadic interval: the nets stay nets. The first addition of a
// uniform random 32-bit key makes every point uniform on the 2^-32 grid, so
// the mean over the points is unbiased; the products with fixed even
// factors and the second key spread each key's effect over the deeper
// digits (a cheap stand-in for Owen's independent coin per interval).
inline std::uint32_t nested_scramble(std::uint32_t reversed, std::uint64_t key) {
    reversed += std::uint32_t(key);
    reversed ^= reversed * 0x9E3779B8u;
    reversed += std::uint32_t(key >> 32);
    reversed ^= reversed * 0x85EBCA6Cu;
    reversed ^= reversed * 0xC2B2AE3Cu;
    return reverse_bits(reversed);
}

// One randomisation of the 2D points: point `index` of a set scrambled with
// its own pair of keys, from the Sobol digits reversed (the first coordinate's
// reversed digits are the index itself). Sets with independent keys are
// independent, and each set is stratified.
struct ScrambledPoints {
    std::uint64_t key_x = 0, key_y = 0;
    glm::dvec2 point(std::uint32_t index, std::uint32_t reversed_y) const {
        constexpr double scale = 1.0 / 4294967296.0;
        // Cell midpoints of the 2^-32 grid: never 0 or 1.
        return {(double(nested_scramble(index, key_x)) + 0.5) * scale,
                (double(nested_scramble(reversed_y, key_y)) + 0.5) * scale};
    }
};

// Orthonormal tangent frame around a unit normal (branchless, Duff et al.).
// How far a ray leaves a surface at `position` so that it does not hit the
// triangle it starts on again: relative to the distance from the origin,
// where float positions lose their precision, plus a hair of `length` (the
// ray's radius, or the scene's size) for points at the origin.
inline float surface_offset(glm::vec3 position, float length) {
    return 1e-5f * std::max({std::abs(position.x), std::abs(position.y), std::abs(position.z)}) +
           1e-6f * length;
}

inline void tangent_frame(glm::dvec3 n, glm::dvec3& t, glm::dvec3& b) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double c = n.x * n.y * a;
    t = {1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x};
    b = {c, sign + n.y * n.y * a, -n.y};
}

}  // namespace deepgi::reference_sampling
