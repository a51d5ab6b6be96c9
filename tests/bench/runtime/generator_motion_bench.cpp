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
#include "bench_harness.hpp"
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
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
    CLI11_PARSE(app, argc, argv);
    return deepgi::bench::run("generator_motion_bench", [&] {
        deepgi::bench::finish(options);
        for (const auto& path : paths)
            if (path != "erratic" && path != "lateral" && path != "dolly")
                throw deepgi::InputError(
                    fmt::format("--paths '{}' is not one of erratic, lateral, dolly", path));
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
                const int total = options.warmup + options.frames;
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
                    for (std::size_t g = 0; g < tested.size(); ++g) {
                        Tally& tally = tallies[g];
                        tally.gbuffer_ms.push_back(gbuffer_ms(*tested[g]));
                        const auto layer1 = tested[g]->read_pass_output("gbuffer-depth-layer1");
                        const auto ao = tested[g]->read_pass_output("ao-raw");
                        const auto e = tested[g]->read_pass_output("radiosity-raw-layer0");
                        for (int y = layout.guard; y < layout.guard + settings.height; ++y) {
                            for (int x = layout.guard; x < layout.guard + settings.width; ++x) {
                                // Nothing in layer 1 counts as infinitely far.
                                const float inf = INFINITY;
                                const float t = truth.at(x, y) > 0.0f ? truth.at(x, y) : inf;
                                const float a = layer1.at(x, y) > 0.0f ? layer1.at(x, y) : inf;
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
                                if (t == inf && a == inf) continue;
                                if (t != inf && a != inf &&
                                    std::abs(a - t) <= 1e-3f * std::max(a, t))
                                    ++tally.equal;
                                else if (a > t)
                                    ++tally.over;
                                else
                                    ++tally.under;
                            }
                        }
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
        return 0;
    });
}
