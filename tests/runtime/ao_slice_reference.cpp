#include "ao_slice_reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace deepgi::test {

namespace {

constexpr float pi = 3.14159265f;
constexpr int sectors = 32;

// G(h) = int_0^h cos(theta - n) |sin theta| dtheta, integrated by hand:
// cos(theta - n) sin(theta) = (sin(2 theta - n) + sin(n)) / 2.
float measure(float h, float n) {
    const float g = 0.25f * (-std::cos(2.0f * h - n) + std::cos(n) + 2.0f * h * std::sin(n));
    return h < 0.0f ? -g : g;
}

struct Slice {
    glm::vec3 view;   // toward the eye
    glm::vec3 along;  // in the slice, perpendicular to view, toward +d
    glm::vec2 direction;
    float n = 0.0f;       // signed angle of the projected normal from view
    float length = 0.0f;  // of the projected normal
};

Slice make_slice(int s, int slices, glm::vec3 position, glm::vec3 normal, float c, float sn) {
    Slice slice;
    const float angle = pi * float(s) / float(slices);
    const float dx = std::cos(angle), dy = std::sin(angle);
    slice.direction = {c * dx - sn * dy, sn * dx + c * dy};
    slice.view = glm::normalize(-position);
    const glm::vec3 d3(slice.direction, 0.0f);
    slice.along = glm::normalize(d3 - slice.view * glm::dot(d3, slice.view));
    const glm::vec3 axis = glm::cross(slice.view, slice.along);
    const glm::vec3 projected = normal - axis * glm::dot(normal, axis);
    slice.length = glm::length(projected);
    const float cos_n =
        slice.length > 0.0f
            ? std::clamp(glm::dot(projected, slice.view) / slice.length, -1.0f, 1.0f)
            : 1.0f;
    slice.n = (glm::dot(projected, slice.along) < 0.0f ? -1.0f : 1.0f) * std::acos(cos_n);
    return slice;
}

float angle_in(const Slice& slice, glm::vec3 w) {
    return std::atan2(glm::dot(w, slice.along), glm::dot(w, slice.view));
}

// The sectors whose centres (i + 1/2) / 32 lie in [lo, hi].
std::uint32_t sector_bits(float lo, float hi) {
    lo = std::clamp(lo, -1.0f, 2.0f);
    hi = std::clamp(hi, -1.0f, 2.0f);
    const int first = std::max(0, int(std::ceil(lo * float(sectors) - 0.5f)));
    const int last = std::min(sectors - 1, int(std::floor(hi * float(sectors) - 0.5f)));
    if (first > last) return 0u;
    const int count = last - first + 1;
    return (count == sectors ? 0xffffffffu : ((1u << count) - 1u)) << first;
}

float pixel_visibility(int x, int y, glm::vec3 position, glm::vec3 normal, float depth,
                       const SaoInputs& inputs, const AoSettings& settings) {
    const FloatImage& base = inputs.pyramid.at(0);
    const bool bitmask = settings.method == AoMethod::bitmask;
    const float radius_squared = settings.radius * settings.radius;
    const float radius_pixels =
        settings.radius * (0.5f * float(base.height)) / (inputs.ray_scale.y * depth);
    const float footprint_bias =
        settings.bias + 0.5f * (2.0f * inputs.ray_scale.y * depth / float(base.height));
    const std::uint32_t hash = pixel_rotation_hash(std::uint32_t(x), std::uint32_t(y));
    const float jitter = float(avalanche32(hash ^ 0x2c1b3c6du) >> 8) * (1.0f / 16777216.0f);
    const float phi = pixel_rotation_angle(std::uint32_t(x), std::uint32_t(y));
    const float c = std::cos(phi), sn = std::sin(phi);
    float visible = 0.0f, open = 0.0f;
    for (int s = 0; s < settings.slices; ++s) {
        const Slice slice = make_slice(s, settings.slices, position, normal, c, sn);
        const float n = slice.n;
        const float start = n - 0.5f * pi;
        // gtao: each side's horizon and the falloff-weighted measure of its
        // rises. bitmask: each sector's falloff, that of the first sample
        // that set it (0: unset).
        float low = start;
        float hidden = 0.0f;
        std::array<float, sectors> sector_falloff{};
        std::uint32_t occupied = 0u;
        for (const float side : {-1.0f, 1.0f}) {
            float horizon = side > 0.0f ? n + 0.5f * pi : start;
            for (int k = 0; k < settings.steps; ++k) {
                const float t = (float(k) + jitter) / float(settings.steps) * radius_pixels;
                const float step = std::min(t, 65536.0f);
                const int ax = int(std::floor(float(x) + 0.5f + side * slice.direction.x * step));
                const int ay = int(std::floor(float(y) + 0.5f + side * slice.direction.y * step));
                if (ax == x && ay == y) continue;
                if (ax < 0 || ay < 0 || ax >= base.width || ay >= base.height) continue;
                for (int layer = 0; layer < settings.layers; ++layer) {
                    const float z = base.at(ax, ay, layer);
                    if (z <= 0.0f) continue;
                    const glm::vec3 front =
                        camera_position(float(ax) + 0.5f, float(ay) + 0.5f, z, inputs);
                    const glm::vec3 w = front - position;
                    const float dd = glm::dot(w, w);
                    if (dd >= radius_squared || glm::dot(w, normal) <= footprint_bias) continue;
                    const float falloff = 1.0f - dd / radius_squared;
                    const float a = angle_in(slice, w);
                    if (!bitmask) {
                        // Side +1's horizon stops at side -1's.
                        const float theta = std::clamp(a, side > 0.0f ? low : start, n + 0.5f * pi);
                        if (side > 0.0f ? theta >= horizon : theta <= horizon) continue;
                        hidden += falloff * std::abs(measure(theta, n) - measure(horizon, n));
                        horizon = theta;
                        continue;
                    }
                    const float b = angle_in(slice, w + glm::normalize(front) * settings.thickness);
                    const std::uint32_t bits =
                        sector_bits((std::min(a, b) - start) / pi, (std::max(a, b) - start) / pi);
                    for (int i = 0; i < sectors; ++i)
                        if ((bits & ~occupied) & (1u << i))
                            sector_falloff[std::size_t(i)] = falloff;
                    occupied |= bits;
                }
            }
            if (side < 0.0f) low = horizon;
        }
        if (bitmask) {
            for (int i = 0; i < sectors; ++i)
                hidden += sector_falloff[std::size_t(i)] *
                          (measure(start + pi * float(i + 1) / float(sectors), n) -
                           measure(start + pi * float(i) / float(sectors), n));
        }
        const float slice_open = measure(n + 0.5f * pi, n) - measure(start, n);
        visible += slice.length * (slice_open - hidden);
        open += slice.length * slice_open;
    }
    return open > 0.0f ? std::pow(std::clamp(visible / open, 0.0f, 1.0f), settings.intensity)
                       : 1.0f;
}

}  // namespace

FloatImage reference_slice_visibility(const SaoInputs& inputs, const AoSettings& settings) {
    const FloatImage& base = inputs.pyramid.at(0);
    FloatImage result;
    result.width = base.width;
    result.height = base.height;
    result.pixels.assign(std::size_t(base.width) * std::size_t(base.height), 1.0f);
    for (int y = 0; y < base.height; ++y) {
        for (int x = 0; x < base.width; ++x) {
            const float depth = base.at(x, y, 0);
            if (depth <= 0.0f) continue;  // sky
            const glm::vec3 position =
                camera_position(float(x) + 0.5f, float(y) + 0.5f, depth, inputs);
            const glm::vec3 normal(inputs.normals.at(x, y, 0), inputs.normals.at(x, y, 1),
                                   inputs.normals.at(x, y, 2));
            result.pixels[std::size_t(y) * std::size_t(base.width) + std::size_t(x)] =
                pixel_visibility(x, y, position, normal, depth, inputs, settings);
        }
    }
    return result;
}

double corner_visibility(double distance, double radius) {
    const double t = distance / radius;
    if (t >= 1.0) return 1.0;
    // Malley: cosine-weighted directions are the unit disk's uniform points
    // lifted to the hemisphere; a direction hits the wall (x = d) within r
    // iff its disk point (u, v) has u > t = d / r, a circular segment of the
    // disk, and it hits at distance d / u, where the falloff is 1 - t^2 / u^2.
    // The occlusion is (1 / pi) times the integral over the segment,
    //   int_t^1 2 sqrt(1 - u^2) (1 - t^2 / u^2) du
    //     = (1 + 2 t^2) acos t - 3 t sqrt(1 - t^2).
    return 1.0 - ((1.0 + 2.0 * t * t) * std::acos(t) - 3.0 * t * std::sqrt(1.0 - t * t)) /
                     std::numbers::pi;
}

}  // namespace deepgi::test
