// The deep radiosity gather evaluated on the CPU from read-back inputs: the
// oracle of the gather's tests and of the temporal filter's convergence test
// (tests/runtime/radiosity_gather_test.cpp, radiosity_temporal_test.cpp).
#pragma once

#include "radiosity_visibility_mirror.hpp"
#include "sao_reference.hpp"
#include "sao_test_support.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <utility>
#include <vector>

namespace deepgi::test {

// The build-time radiosity_taps.glsl pattern, asked of the codegen library.
inline std::vector<spiral::codegen::Tap> build_time_radiosity_taps() {
    const int taps = RADIOSITY_TEST_TAPS;
    const int tau = RADIOSITY_TEST_TAU != 0 ? RADIOSITY_TEST_TAU : spiral::search(taps).tau;
    return spiral::codegen::spiral_taps(taps, tau);
}

// What the gather reads, read back, per layer.
struct GatherInputs {
    std::array<FloatImage, 2> depth;   // metres, 0 = no surface
    std::array<FloatImage, 2> normal;  // camera space
    std::array<FloatImage, 2> albedo;  // linear
    std::array<FloatImage, 2> direct;  // lit radiance
    FloatImage emissive;               // layer 0 only
    glm::vec2 ray_scale{1.0f};
};

inline GatherInputs read_inputs(const Renderer& renderer, const Camera& camera,
                                const RenderSettings& settings) {
    GatherInputs inputs;
    for (int layer = 0; layer < 2; ++layer) {
        inputs.depth[layer] =
            renderer.read_pass_output(fmt::format("gbuffer-depth-layer{}", layer));
        inputs.normal[layer] =
            renderer.read_pass_output(fmt::format("gbuffer-normal-layer{}", layer));
        inputs.albedo[layer] =
            renderer.read_pass_output(fmt::format("gbuffer-albedo-layer{}", layer));
        inputs.direct[layer] =
            renderer.read_pass_output(fmt::format("direct_light-radiance-layer{}", layer));
    }
    inputs.emissive = renderer.read_pass_output("gbuffer-emissive-layer0");
    inputs.ray_scale = camera_ray_scale(camera, settings);
    return inputs;
}

inline glm::vec3 rgb(const FloatImage& image, int x, int y) {
    return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}

inline glm::vec3 position_at(const GatherInputs& inputs, int x, int y, float depth) {
    const float w = float(inputs.depth[0].width);
    const float h = float(inputs.depth[0].height);
    const float ndc_x = (float(x) + 0.5f) / w * 2.0f - 1.0f;
    const float ndc_y = (float(y) + 0.5f) / h * 2.0f - 1.0f;
    return {ndc_x * inputs.ray_scale.x * depth, ndc_y * inputs.ray_scale.y * depth, -depth};
}

// One step of the rotated-grid chain: the texel of a level of size (w, h)
// that texel t of the next level keeps, 2t + ((t.y & 1) ^ 1, (t.x & 1) ^ 1)
// clamped to its size (docs/design.md, section 5.5).
inline glm::ivec2 rotated_grid_kept(glm::ivec2 t, int w, int h) {
    return glm::min(2 * t + glm::ivec2((t.y & 1) ^ 1, (t.x & 1) ^ 1), glm::ivec2(w - 1, h - 1));
}

// The level-0 pixel whose values texel (x, y) of MIP level `level` holds:
// the chain's steps from `level` up to 0.
inline glm::ivec2 rotated_grid_source(glm::ivec2 texel, int level, int width, int height) {
    for (int l = level; l > 0; --l)
        texel =
            rotated_grid_kept(texel, std::max(1, width >> (l - 1)), std::max(1, height >> (l - 1)));
    return texel;
}

// MIP levels the prepare pass and the depth pyramid build.
inline int mip_levels(const RenderSettings& settings, int width, int height) {
    int deepest = 0;
    while ((std::max(width, height) >> (deepest + 1)) > 0) ++deepest;
    return std::min(settings.depth_pyramid.max_mip_level, deepest) + 1;
}

// The deepest level the radiosity's taps read: its own cap
// (radiosity-max-mip) within the levels built.
inline int radiosity_deepest_level(const RenderSettings& settings, int width, int height) {
    return std::min(mip_levels(settings, width, height) - 1, settings.radiosity.max_mip_level);
}

// The radiance a tap reads at each MIP level of one layer: rgb and, in the
// fourth channel, the share of its block's level-0 pixels it stands for (0:
// no surface). Level 0 is direct + emissive (layer 0 only). With the
// prefilter, texel t of level
// m + 1 is the weighted mean of the texels of its 2x2 block at level m that
// lie on the surface of the block's representative r = 2t + corner(t)
// (clamped): normal n with n . n_r >= 0.9 and position P with |n_r . (P -
// P_r)| <= 0.1 |P - P_r|, positions and normals those of the level-0 pixels
// the texels stand for (docs/radiosity.md, "Prefiltered levels"); without
// it, the representative's own radiance, so every level holds one level-0
// pixel's.
inline std::vector<FloatImage> radiance_levels(const GatherInputs& inputs, int layer, int levels,
                                               bool prefilter) {
    const int width = inputs.depth[0].width;
    const int height = inputs.depth[0].height;
    std::vector<FloatImage> result;
    FloatImage base{width, height, 4, std::vector<float>(std::size_t(width) * height * 4)};
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            if (inputs.depth[layer].at(x, y, 0) <= 0.0f) continue;
            glm::vec3 radiance = rgb(inputs.direct[layer], x, y);
            if (layer == 0) radiance += rgb(inputs.emissive, x, y);
            const std::size_t i = 4 * (std::size_t(y) * width + x);
            for (int k = 0; k < 3; ++k) base.pixels[i + k] = radiance[k];
            base.pixels[i + 3] = 1.0f;
        }
    }
    result.push_back(std::move(base));
    // Position and normal of the level-0 pixel texel `t` of `level` stands for.
    const auto geometry = [&](glm::ivec2 t, int level) {
        const glm::ivec2 p = rotated_grid_source(t, level, width, height);
        const float depth = inputs.depth[layer].at(p.x, p.y, 0);
        return std::pair{position_at(inputs, p.x, p.y, depth), rgb(inputs.normal[layer], p.x, p.y)};
    };
    for (int level = 1; level < levels; ++level) {
        const FloatImage& source = result.back();
        const int w = std::max(1, width >> level);
        const int h = std::max(1, height >> level);
        FloatImage next{w, h, 4, std::vector<float>(std::size_t(w) * h * 4)};
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const glm::ivec2 t(x, y);
                const glm::ivec2 chosen = rotated_grid_kept(t, source.width, source.height);
                const auto value = [&](glm::ivec2 at) {
                    return glm::vec4(source.at(at.x, at.y, 0), source.at(at.x, at.y, 1),
                                     source.at(at.x, at.y, 2), source.at(at.x, at.y, 3));
                };
                glm::vec4 out = value(chosen);
                if (prefilter && out.a > 0.0f) {
                    const auto [position, normal] = geometry(chosen, level - 1);
                    glm::vec4 sum(0.0f);
                    for (int j = 0; j < 4; ++j) {
                        const glm::ivec2 at = 2 * t + glm::ivec2(j & 1, j >> 1);
                        if (at.x >= source.width || at.y >= source.height) continue;
                        const glm::vec4 radiance = value(at);
                        if (radiance.a <= 0.0f) continue;
                        const auto [p, n] = geometry(at, level - 1);
                        const glm::vec3 d = p - position;
                        if (glm::dot(n, normal) < 0.9f ||
                            std::abs(glm::dot(normal, d)) > 0.1f * glm::length(d))
                            continue;
                        sum += glm::vec4(glm::vec3(radiance) * radiance.a, radiance.a);
                    }
                    out = glm::vec4(glm::vec3(sum) / sum.a, 0.25f * sum.a);
                }
                const std::size_t i = 4 * (std::size_t(y) * w + x);
                for (int k = 0; k < 4; ++k) next.pixels[i + k] = out[k];
            }
        }
        result.push_back(std::move(next));
    }
    return result;
}

// E (rgb) and confidence of one layer with boost 1 (boost amount 0) and no
// previous frame (first frame, whose pattern rotation is 0): tap i reads MIP
// level clamp(floor(log2(alpha_i R / q)), 0, deepest), deepest the radiosity's
// cap or the pyramid's last level, whichever is smaller, i.e. the position and
// normal of the level-0 pixel that level's rotated-grid texel holds, with Y
// rebuilt at that pixel's centre, and the radiance radiance_levels() gives the
// texel. The estimators, as docs/radiosity.md states them:
//   published: E = 2 pi / M * sum min(B cos_x, clamp),   c = M / (taps * layers)
//   area:      E = 2 pi / N * sum min(B cos_x w, clamp), c = min(1, 2 / N * sum cos_x w),
//              w = alpha_i (z_Y / z_X)^2 cos(phi_Y) cos_y r^2 / (|v|^2 max(cos(view_Y), 0.1))
// with phi_Y the angle between Y's eye ray and the optical axis and view_Y the
// angle between Y's normal and the direction from Y to the eye. With
// `visibility`, a sample that passes the facing tests counts only where
// sample_visible() finds no stored surface between X and Y.
inline std::pair<FloatImage, FloatImage> reference_gather(
    const GatherInputs& inputs, const std::vector<spiral::codegen::Tap>& taps,
    const RenderSettings& render_settings, int layer,
    const VisibilityInputs* visibility = nullptr) {
    const RadiositySettings& settings = render_settings.radiosity;
    const int width = inputs.depth[0].width;
    const int height = inputs.depth[0].height;
    const int deepest = radiosity_deepest_level(render_settings, width, height);
    FloatImage irradiance{width, height, 3, std::vector<float>(std::size_t(width) * height * 3)};
    FloatImage confidence{width, height, 1, std::vector<float>(std::size_t(width) * height)};
    const float radius_squared = settings.radius * settings.radius;
    std::array<std::vector<FloatImage>, 2> radiance;
    for (int j = 0; j < settings.layers; ++j)
        radiance[j] = radiance_levels(inputs, j, deepest + 1, settings.prefilter != 0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float depth = inputs.depth[layer].at(x, y, 0);
            if (depth <= 0.0f) continue;
            const glm::vec3 position = position_at(inputs, x, y, depth);
            const glm::vec3 normal = rgb(inputs.normal[layer], x, y);
            // The area method's disk widens towards the projection of the
            // ball of radius r about X (on the optical axis), at most 1.5
            // times the projection of r at X's depth: k = 1 / sqrt(1 - (r /
            // z_X)^2).
            const bool area = settings.method == RadiosityMethod::area;
            const float t = settings.radius / depth;
            const float widening =
                !area ? 1.0f : (t < 1.0f ? std::min(1.0f / std::sqrt(1.0f - t * t), 1.5f) : 1.5f);
            const float radius_pixels =
                widening * settings.radius * (0.5f * float(height)) / (inputs.ray_scale.y * depth);
            const float phi = pixel_rotation_angle(std::uint32_t(x), std::uint32_t(y));
            const float c = std::cos(phi);
            const float s = std::sin(phi);
            glm::vec3 sum(0.0f);
            float coverage = 0.0f;
            int used = 0;
            for (const auto& tap : taps) {
                const float offset_x =
                    std::clamp((c * tap.x - s * tap.y) * radius_pixels, -65536.0f, 65536.0f);
                const float offset_y =
                    std::clamp((s * tap.x + c * tap.y) * radius_pixels, -65536.0f, 65536.0f);
                const int tap_x = int(std::floor(float(x) + 0.5f + offset_x));
                const int tap_y = int(std::floor(float(y) + 0.5f + offset_y));
                if (tap_x < 0 || tap_y < 0 || tap_x >= width || tap_y >= height) continue;
                const float steps =
                    std::min(tap.alpha * radius_pixels / render_settings.depth_pyramid.q, 65536.0f);
                // floor(log2(steps)) as the highest set bit of floor(steps).
                const int level =
                    steps < 1.0f ? 0 : std::min(int(std::bit_width(unsigned(steps))) - 1, deepest);
                const glm::ivec2 texel = glm::min(
                    glm::ivec2(tap_x, tap_y) >> level,
                    glm::ivec2(std::max(1, width >> level) - 1, std::max(1, height >> level) - 1));
                const glm::ivec2 source = rotated_grid_source(texel, level, width, height);
                for (int j = 0; j < settings.layers; ++j) {
                    const float tap_depth = inputs.depth[j].at(source.x, source.y, 0);
                    if (tap_depth <= 0.0f) continue;
                    const glm::vec3 tap_position =
                        position_at(inputs, source.x, source.y, tap_depth);
                    const glm::vec3 v = tap_position - position;
                    const float vv = glm::dot(v, v);
                    if (vv >= radius_squared || vv <= 0.0f) continue;
                    const glm::vec3 w = v / std::sqrt(vv);
                    const glm::vec3 tap_normal = rgb(inputs.normal[j], source.x, source.y);
                    const float cos_x = glm::dot(w, normal);
                    const float cos_y = -glm::dot(w, tap_normal);
                    if (cos_x <= 0.0f || cos_y <= 0.0f) continue;
                    if (visibility && !sample_visible(*visibility, position, tap_position))
                        continue;
                    float weight = 1.0f;
                    if (settings.method == RadiosityMethod::area) {
                        const glm::vec3 to_eye = -glm::normalize(tap_position);
                        const float cos_phi = to_eye.z;
                        const float cos_view = std::max(glm::dot(tap_normal, to_eye), 0.1f);
                        const float ratio = tap_depth / depth;
                        weight = tap.alpha * widening * widening * ratio * ratio * cos_phi * cos_y *
                                 radius_squared / (vv * cos_view);
                        coverage += cos_x * weight;
                    }
                    const glm::vec3 b = rgb(radiance[j][std::size_t(level)], texel.x, texel.y);
                    sum += glm::min(b * (cos_x * weight), glm::vec3(settings.tap_clamp));
                    ++used;
                }
            }
            const std::size_t i = std::size_t(y) * width + x;
            const float two_pi = 6.2831853f;
            glm::vec3 e(0.0f);
            if (settings.method == RadiosityMethod::area) {
                e = sum * (two_pi / float(taps.size()));
                confidence.pixels[i] = std::min(coverage * 2.0f / float(taps.size()), 1.0f);
            } else {
                e = used > 0 ? sum * (two_pi / float(used)) : glm::vec3(0.0f);
                confidence.pixels[i] = float(used) / float(taps.size() * settings.layers);
            }
            for (int k = 0; k < 3; ++k) irradiance.pixels[3 * i + k] = e[k];
        }
    }
    return {irradiance, confidence};
}

// The relative tolerance of the GPU gather against reference_gather(): 1e-3,
// plus, with the prefilter, one rounding of 2^-11 per level a tap can read.
// The prefiltered levels store each level's means as half floats, each built
// from the level below, and llvmpipe converts toward zero, so the roundings
// add; the CPU's float means have none.
inline float gather_tolerance(const RenderSettings& settings) {
    const int deepest = radiosity_deepest_level(settings, settings.width, settings.height);
    return 1e-3f +
           (settings.radiosity.prefilter != 0 ? float(deepest) * std::ldexp(1.0f, -11) : 0.0f);
}

// The gather tests' frame: 192x108, a shadow map fine enough for cornell's
// lamp-lit walls.
inline RenderSettings gather_test_settings() {
    RenderSettings settings = small_settings(192, 108);
    settings.shadow_map_size = 512;
    return settings;
}

// The largest value of any channel of any pixel (0 for an empty image).
inline float max_value(const FloatImage& image) {
    return image.pixels.empty() ? 0.0f
                                : *std::max_element(image.pixels.begin(), image.pixels.end());
}

}  // namespace deepgi::test
