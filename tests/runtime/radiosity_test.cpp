// Deep radiosity gather against its CPU evaluation and its invariants.
#include "sao_reference.hpp"
#include "sao_test_support.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace deepgi::test {
namespace {

// The build-time radiosity_taps.glsl pattern, asked of the codegen library.
std::vector<spiral::codegen::Tap> build_time_radiosity_taps() {
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

GatherInputs read_inputs(const Renderer& renderer, const Camera& camera,
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

glm::vec3 rgb(const FloatImage& image, int x, int y) {
    return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}

glm::vec3 position_at(const GatherInputs& inputs, int x, int y, float depth) {
    const float w = float(inputs.depth[0].width);
    const float h = float(inputs.depth[0].height);
    const float ndc_x = (float(x) + 0.5f) / w * 2.0f - 1.0f;
    const float ndc_y = (float(y) + 0.5f) / h * 2.0f - 1.0f;
    return {ndc_x * inputs.ray_scale.x * depth, ndc_y * inputs.ray_scale.y * depth, -depth};
}

// E (rgb) and confidence of one layer, from the formula of design.md 3 step 6
// with boost 1 (boost amount 0) and no previous frame (first frame).
std::pair<FloatImage, FloatImage> reference_gather(const GatherInputs& inputs,
                                                   const std::vector<spiral::codegen::Tap>& taps,
                                                   const RadiositySettings& settings, int layer) {
    const int width = inputs.depth[0].width;
    const int height = inputs.depth[0].height;
    FloatImage irradiance{width, height, 3, std::vector<float>(std::size_t(width) * height * 3)};
    FloatImage confidence{width, height, 1, std::vector<float>(std::size_t(width) * height)};
    const float radius_squared = settings.radius * settings.radius;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float depth = inputs.depth[layer].at(x, y, 0);
            if (depth <= 0.0f) continue;
            const glm::vec3 position = position_at(inputs, x, y, depth);
            const glm::vec3 normal = rgb(inputs.normal[layer], x, y);
            const float radius_pixels =
                settings.radius * (0.5f * float(height)) / (inputs.ray_scale.y * depth);
            const float phi = pixel_rotation_angle(std::uint32_t(x), std::uint32_t(y));
            const float c = std::cos(phi);
            const float s = std::sin(phi);
            glm::vec3 sum(0.0f);
            int used = 0;
            for (const auto& tap : taps) {
                const float offset_x =
                    std::clamp((c * tap.x - s * tap.y) * radius_pixels, -65536.0f, 65536.0f);
                const float offset_y =
                    std::clamp((s * tap.x + c * tap.y) * radius_pixels, -65536.0f, 65536.0f);
                const int tap_x = int(std::floor(float(x) + 0.5f + offset_x));
                const int tap_y = int(std::floor(float(y) + 0.5f + offset_y));
                if (tap_x < 0 || tap_y < 0 || tap_x >= width || tap_y >= height) continue;
                for (int j = 0; j < settings.layers; ++j) {
                    const float tap_depth = inputs.depth[j].at(tap_x, tap_y, 0);
                    if (tap_depth <= 0.0f) continue;
                    const glm::vec3 v = position_at(inputs, tap_x, tap_y, tap_depth) - position;
                    const float vv = glm::dot(v, v);
                    if (vv >= radius_squared || vv <= 0.0f) continue;
                    const glm::vec3 w = v / std::sqrt(vv);
                    const float cos_x = glm::dot(w, normal);
                    const float cos_y = -glm::dot(w, rgb(inputs.normal[j], tap_x, tap_y));
                    if (cos_x <= 0.0f || cos_y <= 0.0f) continue;
                    glm::vec3 radiance = rgb(inputs.direct[j], tap_x, tap_y);
                    if (j == 0) radiance += rgb(inputs.emissive, tap_x, tap_y);
                    sum += glm::min(radiance * cos_x, glm::vec3(settings.tap_clamp));
                    ++used;
                }
            }
            const std::size_t i = std::size_t(y) * width + x;
            const glm::vec3 e = used > 0 ? sum * (6.2831853f / float(used)) : glm::vec3(0.0f);
            for (int k = 0; k < 3; ++k) irradiance.pixels[3 * i + k] = e[k];
            confidence.pixels[i] = float(used) / float(taps.size() * settings.layers);
        }
    }
    return {irradiance, confidence};
}

RenderSettings test_settings() {
    RenderSettings settings = small_settings(192, 108);
    settings.shadow_map_size = 512;
    return settings;
}

float max_value(const FloatImage& image) {
    return image.pixels.empty() ? 0.0f
                                : *std::max_element(image.pixels.begin(), image.pixels.end());
}

TEST_CASE("radiosity: the gather matches its CPU evaluation on read-back inputs", "[radiosity]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const auto taps = build_time_radiosity_taps();
    for (const std::string scene_name : {"cornell", "atrium"}) {
        for (int layers : {1, 2}) {
            const Scene scene = make_builtin_scene(scene_name);
            RenderSettings settings = test_settings();
            settings.radiosity.layers = layers;
            Renderer renderer(scene, settings, loader);
            renderer.render(scene.default_camera);
            const GatherInputs inputs = read_inputs(renderer, scene.default_camera, settings);
            for (int layer = 0; layer < 2; ++layer) {
                const auto [expected, expected_confidence] =
                    reference_gather(inputs, taps, settings.radiosity, layer);
                const FloatImage gpu =
                    renderer.read_pass_output(fmt::format("radiosity-raw-layer{}", layer));
                const FloatImage gpu_confidence =
                    renderer.read_pass_output(fmt::format("radiosity-confidence-layer{}", layer));
                std::size_t within = 0, lit = 0;
                const std::size_t pixels = expected_confidence.pixels.size();
                for (std::size_t i = 0; i < pixels; ++i) {
                    const glm::vec3 e(expected.pixels[3 * i], expected.pixels[3 * i + 1],
                                      expected.pixels[3 * i + 2]);
                    const glm::vec3 g(gpu.pixels[3 * i], gpu.pixels[3 * i + 1],
                                      gpu.pixels[3 * i + 2]);
                    // Relative to the pixel's largest channel; zero must stay zero.
                    const float scale = std::max({e.r, e.g, e.b});
                    lit += scale > 1e-3f;
                    const float error =
                        std::max({std::abs(e.r - g.r), std::abs(e.g - g.g), std::abs(e.b - g.b)});
                    const bool irradiance_ok =
                        scale > 0.0f ? error <= 1e-3f * scale : error == 0.0f;
                    const bool confidence_ok =
                        std::abs(gpu_confidence.pixels[i] - expected_confidence.pixels[i]) <= 1e-3f;
                    within += irradiance_ok && confidence_ok;
                }
                const double fraction = double(within) / double(pixels);
                INFO(scene_name << ", " << layers << " layer(s) gathered, layer " << layer << ": "
                                << fraction * 100.0 << "% within 1e-3 relative, " << lit
                                << " lit pixels of " << pixels);
                CHECK(fraction >= 0.999);
                // Enough of the image receives light that the check means something
                // (atrium's layer 1 is mostly hidden floor: about 1% is lit there).
                CHECK(lit > pixels / 200);
            }
        }
    }
}

TEST_CASE("radiosity: black albedo everywhere gives E exactly 0", "[radiosity]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    Scene scene = make_builtin_scene("cornell");
    for (Material& material : scene.materials) {
        material.base_colour = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
        material.emissive = glm::vec3(0.0f);
    }
    RenderSettings settings = test_settings();
    settings.radiosity.rho_prop = 1.0f;
    Renderer renderer(scene, settings, loader);
    for (int frame = 0; frame < 4; ++frame) {
        renderer.render(scene.default_camera);
        for (int layer = 0; layer < 2; ++layer) {
            const FloatImage e =
                renderer.read_pass_output(fmt::format("radiosity-irradiance-layer{}", layer));
            INFO("frame " << frame << ", layer " << layer);
            CHECK(std::all_of(e.pixels.begin(), e.pixels.end(), [](float v) { return v == 0.0f; }));
        }
        // Taps did find surfaces: E is zero because nothing reflects, not
        // because the gather used no taps.
        CHECK(max_value(renderer.read_pass_output("radiosity-confidence-layer0")) > 0.1f);
    }
}

TEST_CASE("radiosity: with black albedo only the emitter lights, and bounces add nothing",
          "[radiosity]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    Scene scene = make_builtin_scene("cornell");
    for (Material& material : scene.materials) material.base_colour = glm::vec4(0, 0, 0, 1);
    // Same frames, same tap rotations: with nothing reflecting, feeding back
    // all of last frame's E (rho_prop 1) must change nothing against none.
    std::vector<FloatImage> results;
    for (float rho_prop : {0.0f, 1.0f}) {
        RenderSettings settings = test_settings();
        settings.radiosity.rho_prop = rho_prop;
        Renderer renderer(scene, settings, loader);
        for (int frame = 0; frame < 4; ++frame) renderer.render(scene.default_camera);
        results.push_back(renderer.read_pass_output("radiosity-raw-layer0"));
    }
    CHECK(max_value(results[0]) > 1.0f);  // the lamp lights the room through the gather
    CHECK(results[1].pixels == results[0].pixels);
}

// Mean of E's red / green ratio over floor pixels whose world x lies in
// [x_min, x_max], near the back half of the room.
float floor_red_over_green(const FloatImage& e, const GatherInputs& inputs, float x_min,
                           float x_max) {
    double ratio = 0.0;
    int count = 0;
    for (int y = 0; y < e.height; ++y) {
        for (int x = 0; x < e.width; ++x) {
            const float depth = inputs.depth[0].at(x, y, 0);
            if (depth <= 0.0f || inputs.normal[0].at(x, y, 1) < 0.9f) continue;
            // The default camera sits at (0, 1, 3.6) looking down -z, unrotated.
            const glm::vec3 p = position_at(inputs, x, y, depth) + glm::vec3(0.0f, 1.0f, 3.6f);
            if (p.y > 0.05f || p.x < x_min || p.x > x_max || p.z > 0.5f) continue;
            const float g = e.at(x, y, 1);
            if (g <= 0.0f) continue;
            ratio += e.at(x, y, 0) / g;
            ++count;
        }
    }
    REQUIRE(count > 20);
    return float(ratio / count);
}

TEST_CASE("radiosity: cornell's floor is redder near the red wall and greener near the green one",
          "[radiosity]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Scene scene = make_builtin_scene("cornell");
    const RenderSettings settings = test_settings();
    Renderer renderer(scene, settings, loader);
    renderer.render(scene.default_camera);
    const GatherInputs inputs = read_inputs(renderer, scene.default_camera, settings);
    const FloatImage e = renderer.read_pass_output("radiosity-irradiance-layer0");
    const float near_red = floor_red_over_green(e, inputs, -1.0f, -0.7f);
    const float near_green = floor_red_over_green(e, inputs, 0.7f, 1.0f);
    INFO("E red/green on the floor: " << near_red << " near the red wall, " << near_green
                                      << " near the green wall");
    CHECK(near_red > 1.2f * near_green);
}

TEST_CASE("radiosity: with alpha 0 the temporal filter returns the raw gather", "[radiosity]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Scene scene = make_builtin_scene("cornell");
    RenderSettings settings = test_settings();
    settings.radiosity.alpha = 0.0f;
    Renderer renderer(scene, settings, loader);
    const auto& keys = scene.camera_path.keys;
    for (std::size_t frame = 0; frame < 4; ++frame) {
        renderer.render(keys[frame % keys.size()]);
        for (int layer = 0; layer < 2; ++layer) {
            const FloatImage raw =
                renderer.read_pass_output(fmt::format("radiosity-raw-layer{}", layer));
            const FloatImage filtered =
                renderer.read_pass_output(fmt::format("radiosity-irradiance-layer{}", layer));
            INFO("frame " << frame << ", layer " << layer);
            CHECK(max_value(raw) > 0.0f);
            CHECK(filtered.pixels == raw.pixels);
        }
    }
}

// Mean of E (all channels) of layer 0 over the frame.
double mean_irradiance(const Renderer& renderer, const char* output) {
    const FloatImage e = renderer.read_pass_output(output);
    double sum = 0.0;
    for (float v : e.pixels) sum += v;
    return sum / double(e.pixels.size());
}

TEST_CASE("radiosity: rho_prop 0 stays at one bounce, rho_prop 1 adds bounces", "[radiosity]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Scene scene = make_builtin_scene("cornell");
    std::vector<double> growth;
    for (float rho_prop : {0.0f, 1.0f}) {
        RenderSettings settings = test_settings();
        settings.radiosity.rho_prop = rho_prop;
        settings.radiosity.alpha = 0.0f;  // the raw gather of each frame, no averaging
        Renderer renderer(scene, settings, loader);
        renderer.render(scene.default_camera);
        const double first = mean_irradiance(renderer, "radiosity-raw-layer0");
        std::vector<double> means{first};
        for (int frame = 1; frame < 8; ++frame) {
            renderer.render(scene.default_camera);
            means.push_back(mean_irradiance(renderer, "radiosity-raw-layer0"));
        }
        INFO("rho_prop " << rho_prop << ": mean E frame 1 " << first << ", frame 8 "
                         << means.back());
        if (rho_prop == 0.0f) {
            // Only the pattern rotates: every frame is the same one bounce, its
            // mean varying with the pattern by a few percent (the small lamp).
            for (double mean : means) CHECK(std::abs(mean - first) <= 0.1 * first);
        } else {
            // Bounces add light over the first frames and then level off.
            CHECK(means[1] > 1.05 * first);
            CHECK(means[3] > means[1]);
            CHECK(means.back() < 4.0 * first);
        }
        growth.push_back(means.back() / first);
    }
    WARN("mean E frame 8 / frame 1: rho_prop 0 " << growth[0] << ", rho_prop 1 " << growth[1]);
}

// Mean relative change of layer 0's filtered E from frame 19 to frame 20 under
// a static camera.
double frame_to_frame_change(const Scene& scene, const ShaderLoader& loader, float alpha) {
    RenderSettings settings = test_settings();
    settings.radiosity.rho_prop = 0.0f;
    settings.radiosity.alpha = alpha;
    Renderer renderer(scene, settings, loader);
    for (int frame = 0; frame < 19; ++frame) renderer.render(scene.default_camera);
    const FloatImage before = renderer.read_pass_output("radiosity-irradiance-layer0");
    renderer.render(scene.default_camera);
    const FloatImage after = renderer.read_pass_output("radiosity-irradiance-layer0");
    double change = 0.0, total = 0.0;
    for (std::size_t i = 0; i < after.pixels.size(); ++i) {
        change += std::abs(after.pixels[i] - before.pixels[i]);
        total += std::abs(after.pixels[i]);
    }
    return change / std::max(total, 1e-12);
}

TEST_CASE("radiosity: under a static camera the temporal filter damps the frame-to-frame change",
          "[radiosity]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Scene scene = make_builtin_scene("cornell");
    const double raw = frame_to_frame_change(scene, loader, 0.0f);
    const double filtered = frame_to_frame_change(scene, loader, 0.85f);
    WARN("mean relative frame-to-frame change of E at frame 20: alpha 0 " << raw << ", alpha 0.85 "
                                                                          << filtered);
    CHECK(raw > 0.0);
    CHECK(filtered < 0.5 * raw);
}

}  // namespace
}  // namespace deepgi::test
