// generator_motion_bench: how wrong each single-pass generator's layer 1 is
// under camera motion, what that does to the AO, and what each costs.
//
// Per scene (default atrium, warehouse) and camera path (erratic rotation,
// fast lateral motion, dolly; below), five renderers follow the same path,
// one frame each in turn: peel (two passes, the oracle: it needs no history)
// and previous, reproject, predict, delay. On each of --frames frames after
// --warmup frames (the path's first frame is a camera cut, so the single-pass
// generators start without history), every generator's layer 1 is compared
// with peel's of the same frame over the viewport's pixels where either has a
// layer 1: equal (depth within 1e-3 relative), over-peeled (deeper than
// peel's, or none where peel has one: its reference was too far) or
// under-peeled (nearer, or one where peel has none: its reference was too
// near). The AO error is |ao-raw - peel's ao-raw| over the viewport's
// layer-0 pixels (this frame's deep SAO before the temporal filter, with the
// default estimator): its mean, and the share of pixels where it exceeds
// 0.02 (the mean hides errors that gather where layer 1 is wrong). The
// radiosity error is sum |E - peel's E| / sum peel's E over the same pixels
// and the three channels, E this frame's raw deep radiosity gather of layer 0
// (radiosity-raw-layer0; its bounce reads each renderer's own history, so a
// wrong layer 1 also errs through last frame's light). The G-buffer milliseconds are
// the median of the pass's timer over the same frames (CPU clock around glFinish, or
// --timing gpu).
//
// --maps DIR writes, for one frame of each path (--maps-frame, default the
// last), what the table counts as images of the viewport: peel's layer-1
// depth (near bright, far dark, black where there is none), and per
// generator its layer 1 against peel's in three colours over a dim grey of
// the scene (layer 0's normals lit from above the camera): blue equal, red
// over-peeled, yellow under-peeled; the dim grey where neither has a layer
// 1. The folder appears whole or not at all (spiral::fileio::AtomicDirectory).
#include "bench_harness.hpp"
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"

#include <fmt/format.h>
#include <spiral/fileio.hpp>

#include <algorithm>
#include <array>
#include <optional>
#include <cmath>
#include <memory>
#include <random>

namespace {

using deepgi::Camera;

const char* const generator_names[] = {"previous", "reproject", "predict", "delay"};
constexpr deepgi::Generator generators[] = {deepgi::Generator::previous,
                                            deepgi::Generator::reproject,
                                            deepgi::Generator::predict, deepgi::Generator::delay};

// The paths start at the scene's default camera; R is its bounding radius.
//   erratic: standing still, turning by a new random rate each frame (yaw up
//            to 0.08 rad, pitch up to 0.03 rad per frame, either way);
//   lateral: sideways at a constant R / 30 per frame;
//   dolly:   forward, R / 4 in all, easing in and out (smoothstep), so it
//            accelerates and decelerates.
std::vector<Camera> camera_path(const deepgi::Scene& scene, const std::string& path, int frames) {
    const Camera base = scene.default_camera;
    const float radius = deepgi::scene_bounding_radius(scene);
    const glm::vec3 forward = deepgi::camera_forward(base);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    std::vector<Camera> cameras;
    std::mt19937 random(1);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    Camera camera = base;
    for (int k = 0; k < frames; ++k) {
        if (path == "erratic") {
            if (k > 0) {
                camera.yaw += 0.08f * unit(random);
                camera.pitch = std::clamp(camera.pitch + 0.03f * unit(random), -1.2f, 1.2f);
            }
        } else if (path == "lateral") {
            camera.position = base.position + right * (float(k) * radius / 30.0f);
        } else {
            const float t = frames > 1 ? float(k) / float(frames - 1) : 0.0f;
            camera.position =
                base.position + forward * (0.25f * radius * t * t * (3.0f - 2.0f * t));
        }
        cameras.push_back(camera);
    }
    return cameras;
}

struct Tally {
    long over = 0, under = 0, equal = 0;
    double ao_error_sum = 0.0;
    long ao_pixels = 0;
    long ao_large = 0;                            // |error| > 0.02
    double e_error_sum = 0.0, e_truth_sum = 0.0;  // radiosity, layer 0, three channels
    std::vector<double> gbuffer_ms;
};

std::string percent(long part, long whole) {
    return whole > 0 ? fmt::format("{:.2f}", 100.0 * double(part) / double(whole)) : "-";
}

// How one generator's layer 1 stands against peel's at a pixel, as the table
// counts it (depths in metres, 0 where there is no layer 1).
enum class Layer1 { none, equal, over, under };

Layer1 classify(float truth, float tested) {
    const float inf = INFINITY;  // nothing in layer 1 counts as infinitely far
    const float t = truth > 0.0f ? truth : inf;
    const float a = tested > 0.0f ? tested : inf;
    if (t == inf && a == inf) return Layer1::none;
    if (t != inf && a != inf && std::abs(a - t) <= 1e-3f * std::max(a, t)) return Layer1::equal;
    return a > t ? Layer1::over : Layer1::under;
}

// The maps of one frame, in the viewport (rows bottom to top, as read back).
struct MapInputs {
    deepgi::FloatImage depth0, normal0, truth;  // peel's
    std::vector<deepgi::FloatImage> layer1;     // each generator's
};

using Rgba = std::array<std::uint8_t, 4>;

// A dim grey of the scene: layer 0's camera-space normal lit from above and
// behind the camera, 0 to 1; -1 where nothing is hit.
float scene_shade(const MapInputs& in, int x, int y) {
    if (in.depth0.at(x, y) <= 0.0f) return -1.0f;
    const glm::vec3 n{in.normal0.at(x, y, 0), in.normal0.at(x, y, 1), in.normal0.at(x, y, 2)};
    return std::max(0.0f, glm::dot(n, glm::normalize(glm::vec3(0.3f, 0.6f, 0.75f))));
}

std::uint8_t byte(float v) {
    return std::uint8_t(std::clamp(v, 0.0f, 255.0f) + 0.5f);
}

std::vector<std::uint8_t> comparison_map(const MapInputs& in, const deepgi::FloatImage& layer1) {
    const int w = in.truth.width, h = in.truth.height;
    std::vector<std::uint8_t> rgba(std::size_t(w) * std::size_t(h) * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float shade = scene_shade(in, x, y);
            const float grey = shade < 0.0f ? 12.0f : 40.0f + 50.0f * shade;
            std::array<float, 3> colour = {grey, grey, grey};
            const float lit = 0.6f + 0.4f * std::max(shade, 0.0f);  // keeps the shapes readable
            switch (classify(in.truth.at(x, y), layer1.at(x, y))) {
                case Layer1::none:
                    break;
                case Layer1::equal:
                    colour = {60.0f * lit, 120.0f * lit, 230.0f * lit};
                    break;
                case Layer1::over:
                    colour = {240.0f * lit, 40.0f * lit, 30.0f * lit};
                    break;
                case Layer1::under:
                    colour = {255.0f * lit, 215.0f * lit, 20.0f * lit};
                    break;
            }
            std::uint8_t* out = &rgba[(std::size_t(y) * w + x) * 4];
            for (int c = 0; c < 3; ++c) out[c] = byte(colour[std::size_t(c)]);
            out[3] = 255;
        }
    return rgba;
}

// Peel's layer-1 depth: from white at its nearest to dark grey at its
// farthest over the frame; black where there is none.
std::vector<std::uint8_t> depth_map(const deepgi::FloatImage& depth) {
    float near = INFINITY, far = 0.0f;
    for (float d : depth.pixels)
        if (d > 0.0f) near = std::min(near, d), far = std::max(far, d);
    std::vector<std::uint8_t> rgba(depth.pixels.size() * 4, 0);
    for (std::size_t i = 0; i < depth.pixels.size(); ++i) {
        const float d = depth.pixels[i];
        const float t = far > near ? (d - near) / (far - near) : 0.0f;
        const std::uint8_t v = d > 0.0f ? byte(255.0f - 200.0f * t) : 0;
        rgba[4 * i] = rgba[4 * i + 1] = rgba[4 * i + 2] = v;
        rgba[4 * i + 3] = 255;
    }
    return rgba;
}

void write_png(spiral::fileio::AtomicDirectory& folder, const std::string& name, int width,
               int height, const std::vector<std::uint8_t>& rgba) {
    const std::vector<std::uint8_t> png = deepgi::encode_png(width, height, rgba);
    folder.write_file(name, png.data(), png.size());
}

deepgi::FloatImage viewport(const deepgi::FloatImage& image, int guard, int width, int height) {
    deepgi::FloatImage out{width, height, image.channels, {}};
    out.pixels.reserve(std::size_t(width) * std::size_t(height) * std::size_t(image.channels));
    for (int y = guard; y < guard + height; ++y)
        for (int x = guard; x < guard + width; ++x)
            for (int c = 0; c < image.channels; ++c) out.pixels.push_back(image.at(x, y, c));
    return out;
}

double gbuffer_ms(const deepgi::Renderer& renderer) {
    for (const auto& timing : renderer.last_timings())
        if (timing.pass == "gbuffer") return timing.milliseconds;
    return 0.0;
}

}  // namespace

int main(int argc, char** argv) {
    deepgi::bench::Options options;
    options.size = "320x180";
    options.scenes = {"atrium", "warehouse"};
    options.frames = 12;
    options.warmup = 2;
    std::vector<std::string> paths = {"erratic", "lateral", "dolly"};
    CLI::App app{
        "generator_motion_bench: each single-pass generator's layer 1 against two-pass peel "
        "of the same frame under camera motion: share over- and under-peeled, the AO error it "
        "causes, G-buffer milliseconds"};
    deepgi::bench::add_options(app, options);
    app.add_option("--paths", paths, "Camera paths: erratic, lateral, dolly")->delimiter(',');
    std::string maps;
    std::optional<int> maps_frame;
    app.add_option("--maps", maps,
                   "folder for PNG maps of one frame per path: peel's layer-1 depth, and each "
                   "generator's layer 1 against it (blue equal, red over-, yellow under-peeled)");
    app.add_option("--maps-frame", maps_frame,
                   "the frame of each path the maps show, counted from its first (the cut); "
                   "default the last");
    CLI11_PARSE(app, argc, argv);
    return deepgi::bench::run("generator_motion_bench", [&] {
        deepgi::bench::finish(options);
        for (const auto& path : paths)
            if (path != "erratic" && path != "lateral" && path != "dolly")
                throw deepgi::InputError(
                    fmt::format("--paths '{}' is not one of erratic, lateral, dolly", path));
        const int total = options.warmup + options.frames;
        const int map_frame = maps_frame.value_or(total - 1);
        if (map_frame < options.warmup || map_frame >= total)
            throw deepgi::InputError(
                fmt::format("--maps-frame {} is not a measured frame ({} to {})", map_frame,
                            options.warmup, total - 1));
        std::optional<spiral::fileio::AtomicDirectory> map_folder;
        if (!maps.empty()) {
            try {
                spiral::fileio::check_directory_target(maps, ".png");
            } catch (const spiral::fileio::WriteError& error) {
                throw deepgi::InputError(fmt::format("--maps: {}", error.what()));
            }
            map_folder.emplace(maps, ".png");
        }
        int maps_written = 0;
        const deepgi::RenderSettings settings = deepgi::bench::settings_for(options);
        deepgi::validate(settings);
        deepgi::HeadlessContext context;
        const deepgi::ShaderLoader loader = deepgi::ShaderLoader::from_build_configuration();
        const deepgi::FrameLayout layout = deepgi::frame_layout(settings);
        std::string measured;
        fmt::print(
            "| scene | path | generator | over-peeled (%) | under-peeled (%) | equal (%) | AO "
            "mean abs error | AO error > 0.02 (%) | E relative error (%) | gbuffer (ms) "
            "|\n|---|---|---|---|---|---|---|---|---|---|\n");
        for (const auto& name : options.scenes) {
            const deepgi::Scene scene = deepgi::load_scene(name);
            auto make = [&](deepgi::Generator generator) {
                deepgi::RenderSettings s = settings;
                s.generator = generator;
                return std::make_unique<deepgi::Renderer>(scene, s, loader);
            };
            const auto peel = make(deepgi::Generator::peel);
            std::vector<std::unique_ptr<deepgi::Renderer>> tested;
            for (deepgi::Generator generator : generators) tested.push_back(make(generator));
            if (measured.empty()) measured = deepgi::bench::measured_on(*peel, options);
            for (const auto& path : paths) {
                // One camera more: delay's next camera on the last frame.
                const std::vector<Camera> cameras = camera_path(scene, path, total + 1);
                std::vector<Tally> tallies(tested.size());
                std::vector<double> peel_ms;
                for (int k = 0; k < total; ++k) {
                    const auto motion =
                        k == 0 ? deepgi::CameraMotion::cut : deepgi::CameraMotion::continuous;
                    peel->render(cameras[k], motion);
                    for (auto& renderer : tested)
                        renderer->render(cameras[k], cameras[k + 1], motion);
                    if (k < options.warmup) continue;
                    peel_ms.push_back(gbuffer_ms(*peel));
                    const deepgi::FloatImage depth0 =
                        peel->read_pass_output("gbuffer-depth-layer0");
                    const deepgi::FloatImage truth = peel->read_pass_output("gbuffer-depth-layer1");
                    const deepgi::FloatImage truth_ao = peel->read_pass_output("ao-raw");
                    const deepgi::FloatImage truth_e =
                        peel->read_pass_output("radiosity-raw-layer0");
                    std::optional<MapInputs> map;
                    if (map_folder && k == map_frame) {
                        auto cut = [&](const deepgi::FloatImage& image) {
                            return viewport(image, layout.guard, settings.width, settings.height);
                        };
                        map.emplace();
                        map->depth0 = cut(depth0);
                        map->normal0 = cut(peel->read_pass_output("gbuffer-normal-layer0"));
                        map->truth = cut(truth);
                    }
                    for (std::size_t g = 0; g < tested.size(); ++g) {
                        Tally& tally = tallies[g];
                        tally.gbuffer_ms.push_back(gbuffer_ms(*tested[g]));
                        const auto layer1 = tested[g]->read_pass_output("gbuffer-depth-layer1");
                        if (map)
                            map->layer1.push_back(
                                viewport(layer1, layout.guard, settings.width, settings.height));
                        const auto ao = tested[g]->read_pass_output("ao-raw");
                        const auto e = tested[g]->read_pass_output("radiosity-raw-layer0");
                        for (int y = layout.guard; y < layout.guard + settings.height; ++y) {
                            for (int x = layout.guard; x < layout.guard + settings.width; ++x) {
                                if (depth0.at(x, y) > 0.0f) {
                                    const float error = std::abs(ao.at(x, y) - truth_ao.at(x, y));
                                    tally.ao_error_sum += error;
                                    tally.ao_large += error > 0.02f ? 1 : 0;
                                    ++tally.ao_pixels;
                                    for (int c = 0; c < 3; ++c) {
                                        tally.e_error_sum +=
                                            std::abs(e.at(x, y, c) - truth_e.at(x, y, c));
                                        tally.e_truth_sum += truth_e.at(x, y, c);
                                    }
                                }
                                switch (classify(truth.at(x, y), layer1.at(x, y))) {
                                    case Layer1::none:
                                        break;
                                    case Layer1::equal:
                                        ++tally.equal;
                                        break;
                                    case Layer1::over:
                                        ++tally.over;
                                        break;
                                    case Layer1::under:
                                        ++tally.under;
                                        break;
                                }
                            }
                        }
                    }
                    if (map) {
                        const std::string prefix = fmt::format("{}-{}-", name, path);
                        write_png(*map_folder, prefix + "peel.png", settings.width, settings.height,
                                  depth_map(map->truth));
                        for (std::size_t g = 0; g < tested.size(); ++g)
                            write_png(*map_folder, prefix + generator_names[g] + ".png",
                                      settings.width, settings.height,
                                      comparison_map(*map, map->layer1[g]));
                        maps_written += 1 + int(tested.size());
                    }
                }
                fmt::print("| {} | {} | peel | - | - | - | - | - | - | {:.2f} |\n", name, path,
                           deepgi::bench::median(peel_ms));
                for (std::size_t g = 0; g < tested.size(); ++g) {
                    const Tally& t = tallies[g];
                    const long layer1 = t.over + t.under + t.equal;
                    fmt::print("| {} | {} | {} | {} | {} | {} | {:.4f} | {} | {:.2f} | {:.2f} |\n",
                               name, path, generator_names[g], percent(t.over, layer1),
                               percent(t.under, layer1), percent(t.equal, layer1),
                               t.ao_pixels > 0 ? t.ao_error_sum / double(t.ao_pixels) : 0.0,
                               percent(t.ao_large, t.ao_pixels),
                               t.e_truth_sum > 0.0 ? 100.0 * t.e_error_sum / t.e_truth_sum : 0.0,
                               deepgi::bench::median(t.gbuffer_ms));
                }
                std::fflush(stdout);
            }
        }
        fmt::print("\n{}\n", measured);
        if (map_folder) {
            map_folder->commit();
            fmt::print("maps: {} images of frame {} of each path in {}\n", maps_written, map_frame,
                       maps);
        }
        return 0;
    });
}
