// Mirror reflections (reflection.frag) on the gallery scene, against a CPU
// march written from the definition in docs/reflections.md: every sample of
// the reflected ray tested against the read-back layers, their normals and
// back faces, with no long steps. The shader's long steps over its
// nearest-depth pyramid must not change a single decision.
#include "deepgi/context.hpp"
#include "deepgi/renderer.hpp"
#include "runtime_support.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>

using namespace deepgi;

namespace {

RenderSettings gallery_settings(int layers) {
    RenderSettings settings;
    settings.width = 320;
    settings.height = 180;
    settings.shadow_map_size = 512;
    settings.reflection.layers = layers;
    return settings;
}

struct ReadBack {
    FloatImage depth[2], normal[2], back[2], albedo[2];
    FloatImage hit, jitter, weight, compose;
};

ReadBack read_back(const Renderer& renderer) {
    ReadBack r;
    for (int layer = 0; layer < 2; ++layer) {
        r.depth[layer] = renderer.read_pass_output(fmt::format("gbuffer-depth-layer{}", layer));
        r.normal[layer] = renderer.read_pass_output(fmt::format("gbuffer-normal-layer{}", layer));
        r.albedo[layer] = renderer.read_pass_output(fmt::format("gbuffer-albedo-layer{}", layer));
        r.back[layer] = renderer.read_pass_output(fmt::format("backface-depth-layer{}", layer));
    }
    r.hit = renderer.read_pass_output("reflection-hit");
    r.jitter = renderer.read_pass_output("reflection-jitter");
    r.weight = renderer.read_pass_output("reflection-weight");
    r.compose = renderer.read_pass_output("compose-radiance");
    return r;
}

struct CpuHit {
    int layer = -1;  // -1: nothing hit (or the ray left the buffer)
    int x = 0, y = 0;
};

// The march of docs/reflections.md, sample by sample.
struct CpuMarch {
    const ReadBack& r;
    glm::vec2 ray_scale;
    float near_plane;
    glm::vec2 size;
    float distance;
    int steps;
    int layers;
    float thickness;

    glm::vec3 position_at(glm::vec2 centre, float depth) const {
        const glm::vec2 ndc = centre / size * 2.0f - 1.0f;
        return {ndc * ray_scale * depth, -depth};
    }
    glm::vec3 normal(int layer, int x, int y) const {
        const FloatImage& n = r.normal[layer];
        return {n.at(x, y, 0), n.at(x, y, 1), n.at(x, y, 2)};
    }

    CpuHit trace(int px, int py, float jitter) const {
        const glm::vec3 origin =
            position_at(glm::vec2(float(px) + 0.5f, float(py) + 0.5f), r.depth[0].at(px, py));
        const glm::vec3 n = normal(0, px, py);
        const glm::vec3 v = glm::normalize(origin);
        const glm::vec3 direction = glm::normalize(v - 2.0f * glm::dot(n, v) * n);
        const float step = distance / float(steps);
        for (int k = 0; k < steps; ++k) {
            const glm::vec3 q = origin + direction * ((float(k) + jitter) * step);
            const float z = -q.z;
            if (z <= near_plane) return {};
            const glm::vec2 at = (glm::vec2(q) / (z * ray_scale) * 0.5f + 0.5f) * size;
            if (at.x < 0.0f || at.y < 0.0f || at.x >= size.x || at.y >= size.y) return {};
            const int x = int(at.x), y = int(at.y);
            for (int layer = 0; layer < layers; ++layer) {
                const float depth = r.depth[layer].at(x, y);
                if (depth <= 0.0f || z <= depth) continue;
                const float back = r.back[layer].at(x, y);
                const float end =
                    back > 0.0f ? std::max(back, depth + 2.0f * step) : depth + thickness;
                if (z >= end) continue;
                const glm::vec3 surface =
                    position_at(glm::vec2(float(x) + 0.5f, float(y) + 0.5f), depth);
                if (glm::dot(q - surface, normal(layer, x, y)) >= -1e-3f * z) continue;
                return {layer, x, y};
            }
        }
        return {};
    }
};

CpuMarch make_march(const ReadBack& r, const Scene& scene, const RenderSettings& settings) {
    const glm::mat4 projection = guard_band_projection(scene.default_camera, settings);
    const FrameLayout layout = frame_layout(settings);
    const float radius = 0.5f * glm::length(scene.bounds.max - scene.bounds.min);
    return {r,
            {1.0f / projection[0][0], 1.0f / projection[1][1]},
            scene.default_camera.near_plane,
            {float(layout.internal_width), float(layout.internal_height)},
            reflection_distance(settings, radius),
            settings.reflection.steps,
            settings.reflection.layers,
            settings.ao.thickness};
}

bool is_mirror(const ReadBack& r, int x, int y) {
    return r.hit.at(x, y, 2) > -1.5f;
}

}  // namespace

TEST_CASE("reflection: a CPU march on the read-back layers agrees with the shader",
          "[reflection]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("gallery");
    for (int layers : {1, 2}) {
        const RenderSettings settings = gallery_settings(layers);
        Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
        renderer.render(scene.default_camera);
        const ReadBack r = read_back(renderer);
        const CpuMarch march = make_march(r, scene, settings);
        int mirrors = 0, agree = 0, hits[2] = {0, 0};
        for (int y = 0; y < r.hit.height; ++y) {
            for (int x = 0; x < r.hit.width; ++x) {
                if (!is_mirror(r, x, y)) continue;
                ++mirrors;
                const CpuHit cpu = march.trace(x, y, r.jitter.at(x, y));
                const int gpu_layer = int(std::lround(r.hit.at(x, y, 2)));
                if (cpu.layer >= 0) ++hits[cpu.layer];
                const bool same =
                    gpu_layer == cpu.layer && (cpu.layer < 0 || (int(r.hit.at(x, y, 0)) == cpu.x &&
                                                                 int(r.hit.at(x, y, 1)) == cpu.y));
                agree += same ? 1 : 0;
            }
        }
        const double share = double(agree) / double(std::max(mirrors, 1));
        std::cout << fmt::format(
            "gallery, {} layer(s): {} mirror pixels, CPU hits {} / {}, "
            "agreement {:.5f}\n",
            layers, mirrors, hits[0], hits[1], share);
        REQUIRE(mirrors > r.hit.width * r.hit.height / 5);  // the floor fills much of the view
        REQUIRE(hits[0] > mirrors / 4);
        if (layers == 2) REQUIRE(hits[1] > 100);  // the second layer really is reached
        if (layers == 1) REQUIRE(hits[1] == 0);
        CHECK(share >= 0.999);
    }
}

TEST_CASE("reflection: each level of the nearest-depth pyramid is the minimum of what it covers",
          "[reflection]") {
    // The long steps are safe only if every texel of level m holds the
    // nearest layer-0 depth of all level-0 texels it covers; the last row and
    // column of a floor-sized level also cover the finer level's odd last one.
    HeadlessContext context;
    const Scene scene = make_builtin_scene("gallery");
    Renderer renderer(scene, gallery_settings(2), ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
    FloatImage finer = renderer.read_pass_output("reflection-nearest-level0");
    int wrong = 0;
    for (int y = 0; y < finer.height; ++y)
        for (int x = 0; x < finer.width; ++x)
            wrong += finer.at(x, y) != (depth.at(x, y) > 0.0f ? depth.at(x, y) : 3.0e38f) ? 1 : 0;
    CHECK(wrong == 0);
    int levels = 1;
    for (int level = 1; finer.width > 1 || finer.height > 1; ++level, ++levels) {
        const FloatImage coarse =
            renderer.read_pass_output(fmt::format("reflection-nearest-level{}", level));
        REQUIRE(coarse.width == std::max(finer.width / 2, 1));
        REQUIRE(coarse.height == std::max(finer.height / 2, 1));
        wrong = 0;
        for (int y = 0; y < coarse.height; ++y) {
            for (int x = 0; x < coarse.width; ++x) {
                const int x1 = x == coarse.width - 1 ? finer.width - 1 : 2 * x + 1;
                const int y1 = y == coarse.height - 1 ? finer.height - 1 : 2 * y + 1;
                float nearest = 3.0e38f;
                for (int yy = 2 * y; yy <= std::min(y1, finer.height - 1); ++yy)
                    for (int xx = 2 * x; xx <= std::min(x1, finer.width - 1); ++xx)
                        nearest = std::min(nearest, finer.at(xx, yy));
                wrong += coarse.at(x, y) != nearest ? 1 : 0;
            }
        }
        INFO("level " << level);
        CHECK(wrong == 0);
        finer = coarse;
    }
    REQUIRE(levels >= 8);
}

TEST_CASE("reflection: the mirror under the red box shows red where the CPU march hits it",
          "[reflection]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("gallery");
    const RenderSettings settings = gallery_settings(2);
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    const ReadBack r = read_back(renderer);
    const CpuMarch march = make_march(r, scene, settings);
    int predicted = 0, red_shown = 0;
    for (int y = 0; y < r.hit.height; ++y) {
        for (int x = 0; x < r.hit.width; ++x) {
            if (!is_mirror(r, x, y)) continue;
            const CpuHit cpu = march.trace(x, y, r.jitter.at(x, y));
            if (cpu.layer < 0 || r.weight.at(x, y) < 0.99f) continue;
            const FloatImage& albedo = r.albedo[cpu.layer];
            const bool red_texel = albedo.at(cpu.x, cpu.y, 0) > 0.5f &&
                                   albedo.at(cpu.x, cpu.y, 1) < 0.15f &&
                                   albedo.at(cpu.x, cpu.y, 2) < 0.15f;
            if (!red_texel) continue;
            ++predicted;
            const float red = r.compose.at(x, y, 0);
            if (red > 2.0f * r.compose.at(x, y, 1) && red > 2.0f * r.compose.at(x, y, 2) &&
                red > 0.01f)
                ++red_shown;
        }
    }
    std::cout << fmt::format("red box reflected: {} pixels predicted, {} red\n", predicted,
                             red_shown);
    REQUIRE(predicted > 50);
    CHECK(double(red_shown) >= 0.999 * double(predicted));
}

TEST_CASE("reflection: the hidden sculpture is reflected with two layers and not with one",
          "[reflection]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("gallery");
    auto green_mirror_pixels = [&](int layers, int& green_in_layer0, int& green_in_layer1) {
        const RenderSettings settings = gallery_settings(layers);
        Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
        renderer.render(scene.default_camera);
        const ReadBack r = read_back(renderer);
        auto green = [](const FloatImage& image, int x, int y) {
            const float g = image.at(x, y, 1);
            return g > 0.01f && g > 2.0f * image.at(x, y, 0) && g > 2.0f * image.at(x, y, 2);
        };
        int count = 0;
        green_in_layer0 = green_in_layer1 = 0;
        for (int y = 0; y < r.hit.height; ++y) {
            for (int x = 0; x < r.hit.width; ++x) {
                green_in_layer0 += green(r.albedo[0], x, y) ? 1 : 0;
                green_in_layer1 += green(r.albedo[1], x, y) ? 1 : 0;
                if (is_mirror(r, x, y) && green(r.compose, x, y)) ++count;
            }
        }
        return count;
    };
    int layer0_green = 0, layer1_green = 0;
    const int with_two = green_mirror_pixels(2, layer0_green, layer1_green);
    // The camera does not see the sculpture; the second layer does.
    REQUIRE(layer0_green == 0);
    REQUIRE(layer1_green > 100);
    const int with_one = green_mirror_pixels(1, layer0_green, layer1_green);
    std::cout << fmt::format("green mirror pixels: {} with two layers, {} with one\n", with_two,
                             with_one);
    CHECK(with_two > 50);
    CHECK(with_one == 0);
}

TEST_CASE("reflection: the jitter advances by the frame sequence's v every frame", "[reflection]") {
    // The frame sequence's v (shaders/temporal_sequence.h) is Sobol's second
    // dimension, from its definition and not from the shared header: v_k is
    // the xor of the direction numbers of k's bits, 1/2, 3/4, ... (columns of
    // Pascal's triangle mod 2), so v_0 = 0, v_1 = 1/2, v_2 = 3/4 and the
    // jitter steps by 1/2, then by 1/4 (mod 1).
    const std::array<float, 2> v_steps = {0.5f, 0.25f};
    HeadlessContext context;
    const Scene scene = make_builtin_scene("gallery");
    Renderer renderer(scene, gallery_settings(2), ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    std::array<FloatImage, 3> jitter;
    jitter[0] = renderer.read_pass_output("reflection-jitter");
    const FloatImage hit = renderer.read_pass_output("reflection-hit");
    for (int frame = 1; frame < 3; ++frame) {
        renderer.render(scene.default_camera);
        jitter[std::size_t(frame)] = renderer.read_pass_output("reflection-jitter");
    }
    int mirrors = 0;
    std::array<int, 2> advanced = {0, 0};
    for (int y = 0; y < hit.height; ++y) {
        for (int x = 0; x < hit.width; ++x) {
            if (hit.at(x, y, 2) < -1.5f) continue;
            ++mirrors;
            for (std::size_t i = 0; i < 2; ++i) {
                float step = jitter[i + 1].at(x, y) - jitter[i].at(x, y);
                step -= std::floor(step);
                if (std::abs(step - v_steps[i]) < 1e-4f) ++advanced[i];
            }
        }
    }
    REQUIRE(mirrors > 0);
    CHECK(advanced[0] == mirrors);
    CHECK(advanced[1] == mirrors);
}

TEST_CASE(
    "reflection: no NaN or Inf for rays leaving the screen, facing the camera, grazing or "
    "starting at the guard band",
    "[reflection]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("gallery");
    struct Case {
        const char* what;
        Camera camera;
    };
    auto camera = [&](glm::vec3 position, float yaw, float pitch) {
        Camera c = scene.default_camera;
        c.position = position;
        c.yaw = glm::radians(yaw);
        c.pitch = glm::radians(pitch);
        return c;
    };
    const Case cases[] = {
        {"straight down: rays point at the camera", camera({0.0f, 2.5f, 0.5f}, 0.0f, -90.0f)},
        {"grazing: the eye just above the mirror", camera({0.0f, 0.02f, 2.5f}, 0.0f, 0.0f)},
        {"rays leaving the top of the screen", camera({0.0f, 1.7f, 2.0f}, 0.0f, -45.0f)},
        {"mirror only in the guard band", camera({0.0f, 1.5f, 2.5f}, 0.0f, 33.0f)},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        for (int layers : {1, 2}) {
            Renderer renderer(scene, gallery_settings(layers),
                              ShaderLoader::from_build_configuration());
            renderer.render(c.camera);
            renderer.render(c.camera);
            for (const char* name : {"reflection-radiance", "reflection-weight", "reflection-hit",
                                     "reflection-temporal", "compose-radiance"})
                CHECK(test::all_finite(renderer.read_pass_output(name)));
        }
    }
}

TEST_CASE(
    "reflection: under a still camera the filtered reflection is the running mean of every "
    "frame's march, and under motion this frame's march alone",
    "[reflection]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("gallery");
    RenderSettings settings = gallery_settings(2);
    settings.width = 160;
    settings.height = 90;
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    std::vector<double> sum;
    std::size_t checked = 0, agree = 0;
    double first_step = 0.0, last_step = 0.0;  // mean |change| of the filtered image
    FloatImage previous;
    constexpr int frames = 24;
    for (int frame = 1; frame <= frames; ++frame) {
        renderer.render(scene.default_camera);
        const FloatImage raw = renderer.read_pass_output("reflection-radiance");
        const FloatImage filtered = renderer.read_pass_output("reflection-temporal");
        const FloatImage hit = renderer.read_pass_output("reflection-hit");
        sum.resize(raw.pixels.size(), 0.0);
        double change = 0.0;
        std::size_t mirrors = 0;
        for (int y = 0; y < raw.height; ++y) {
            for (int x = 0; x < raw.width; ++x) {
                if (hit.at(x, y, 2) < -1.5f) continue;  // not a mirror
                ++mirrors;
                for (int c = 0; c < 3; ++c) {
                    const std::size_t i = (std::size_t(y) * raw.width + x) * 3 + c;
                    sum[i] += raw.pixels[i];
                    const double mean = sum[i] / frame;
                    ++checked;
                    agree += std::abs(filtered.pixels[i] - mean) <= 1e-4 + 1e-3 * std::abs(mean);
                    if (frame > 1) change += std::abs(filtered.pixels[i] - previous.pixels[i]);
                }
            }
        }
        REQUIRE(mirrors > 1000);
        if (frame == 2) first_step = change / double(mirrors);
        if (frame == frames) last_step = change / double(mirrors);
        previous = filtered;
    }
    INFO(agree << " of " << checked << " mirror channels are the running mean");
    CHECK(agree == checked);
    // The running mean's step falls as 1/n: frame 24's is ~1/12 of frame 2's.
    INFO("mean change of the filtered reflection: frame 2 " << first_step << ", frame " << frames
                                                            << " " << last_step);
    CHECK(first_step > 0.0);
    CHECK(last_step < first_step / 6.0);

    // A sideways step: every mirror pixel that moved on screen takes this
    // frame's march alone.
    Camera moved = scene.default_camera;
    moved.position.x += 0.05f;
    renderer.render(moved, CameraMotion::continuous);
    const FloatImage raw = renderer.read_pass_output("reflection-radiance");
    const FloatImage filtered = renderer.read_pass_output("reflection-temporal");
    const FloatImage hit = renderer.read_pass_output("reflection-hit");
    const FloatImage motion = renderer.read_pass_output("gbuffer-motion-layer0");
    std::size_t moving = 0, fresh = 0;
    for (int y = 0; y < raw.height; ++y) {
        for (int x = 0; x < raw.width; ++x) {
            if (hit.at(x, y, 2) < -1.5f) continue;
            if (std::abs(motion.at(x, y, 0)) <= 1.0f / 64.0f &&
                std::abs(motion.at(x, y, 1)) <= 1.0f / 64.0f)
                continue;
            ++moving;
            bool same = true;
            for (int c = 0; c < 3; ++c) same = same && filtered.at(x, y, c) == raw.at(x, y, c);
            fresh += same;
        }
    }
    REQUIRE(moving > 1000);
    CHECK(fresh == moving);
}
