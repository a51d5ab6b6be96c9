// The bilateral blur's CPU evaluation (blur_reference.hpp).
#include "blur_reference.hpp"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>

namespace deepgi::test {

Guide make_guide(int width, int height,
                 const std::function<std::pair<float, glm::vec3>(int, int)>& surface) {
    Guide guide;
    guide.width = width;
    guide.height = height;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            auto [depth, normal] = surface(x, y);
            guide.depth.push_back(depth);
            guide.normal.push_back(glm::normalize(normal));
        }
    }
    return guide;
}

glm::vec2 encode_octahedral(glm::vec3 n) {
    n /= std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    if (n.z >= 0.0f) return {n.x, n.y};
    return {(1.0f - std::abs(n.y)) * (n.x >= 0.0f ? 1.0f : -1.0f),
            (1.0f - std::abs(n.x)) * (n.y >= 0.0f ? 1.0f : -1.0f)};
}

namespace {

// The shader's decode of an octahedral normal stored as RG16F.
glm::vec3 decode_stored_normal(glm::vec3 n) {
    glm::vec2 e = encode_octahedral(n);
    e = {glm::unpackHalf1x16(glm::packHalf1x16(e.x)), glm::unpackHalf1x16(glm::packHalf1x16(e.y))};
    glm::vec3 d(e.x, e.y, 1.0f - std::abs(e.x) - std::abs(e.y));
    const float t = std::max(-d.z, 0.0f);
    d.x += d.x >= 0.0f ? -t : t;
    d.y += d.y >= 0.0f ? -t : t;
    return glm::normalize(d);
}

}  // namespace

std::vector<Signal> cpu_blur(const Guide& guide, std::vector<Signal> sources,
                             const spiral::codegen::BlurKernel& kernel,
                             const BlurSettings& parameters, double world_extent) {
    const int w = guide.width;
    const int h = guide.height;
    std::vector<glm::vec3> normal(guide.normal.size());
    for (std::size_t i = 0; i < normal.size(); ++i)
        normal[i] = decode_stored_normal(guide.normal[i]);
    auto position = [&](int x, int y) {
        const float d = guide.at_depth(x, y);
        const glm::vec2 ndc((float(x) + 0.5f) / float(w) * 2.0f - 1.0f,
                            (float(y) + 0.5f) / float(h) * 2.0f - 1.0f);
        return glm::vec3(ndc.x * 0.7f * d, ndc.y * 0.45f * d, -d);
    };
    for (int pass = 0; pass < 2; ++pass) {
        const int dx = pass == 0 ? 1 : 0;
        const int dy = pass == 0 ? 0 : 1;
        std::vector<Signal> next = sources;
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const std::size_t centre = std::size_t(y) * std::size_t(w) + std::size_t(x);
                const float depth = guide.depth[centre];
                if (depth <= 0.0f) continue;
                const glm::vec3 p = position(x, y);
                const glm::vec3 n = normal[centre];
                std::vector<std::pair<std::size_t, double>> taps{
                    {centre, kernel.weights[std::size_t(kernel.radius)]}};
                for (int k = -kernel.radius; k <= kernel.radius; ++k) {
                    const int tx = x + k * dx;
                    const int ty = y + k * dy;
                    if (k == 0 || tx < 0 || ty < 0 || tx >= w || ty >= h) continue;
                    const std::size_t tap = std::size_t(ty) * std::size_t(w) + std::size_t(tx);
                    const float tap_depth = guide.depth[tap];
                    if (tap_depth <= 0.0f) continue;
                    const double g_d =
                        std::max(0.0, 1.0 - std::abs(double(tap_depth) - depth) /
                                                (double(parameters.depth_tolerance) * depth));
                    const double g_n = std::pow(std::max(double(glm::dot(normal[tap], n)), 0.0),
                                                double(parameters.normal_power));
                    const double g_p =
                        std::max(0.0, 1.0 - std::abs(double(glm::dot(position(tx, ty) - p, n))) /
                                                (double(parameters.plane_tolerance) * depth));
                    const glm::dvec3 offset(position(tx, ty) - p);
                    const double g_e = world_extent > 0.0
                                           ? std::max(0.0, 1.0 - glm::dot(offset, offset) /
                                                                     (world_extent * world_extent))
                                           : 1.0;
                    taps.emplace_back(tap, kernel.weights[std::size_t(k + kernel.radius)] * g_d *
                                               g_n * g_p * g_e);
                }
                double total = 0.0;
                for (const auto& [tap, weight] : taps) total += weight;
                for (std::size_t s = 0; s < sources.size(); ++s) {
                    const int c = sources[s].channels;
                    for (int channel = 0; channel < c; ++channel) {
                        double sum = 0.0;
                        for (const auto& [tap, weight] : taps)
                            sum += weight *
                                   sources[s].values[tap * std::size_t(c) + std::size_t(channel)];
                        next[s].values[centre * std::size_t(c) + std::size_t(channel)] =
                            float(sum / total);
                    }
                }
            }
        }
        sources = std::move(next);
    }
    return sources;
}

}  // namespace deepgi::test
