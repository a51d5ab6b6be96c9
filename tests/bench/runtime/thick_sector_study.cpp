// thick_sector_study: the thick spiral's first-frame error against the ray
// tracer per tap count N and azimuth sector count S (docs/deep-sao.md, "The
// thick spiral"). Each (N, S) runs the production sao.frag with a tap header
// the codegen library writes for (N, optimal tau), and S fixed by a
// `#define AO_THICK_SECTORS` in that header (0: the shader's own count for
// N, shaders/ao_thick_sectors.h). The truth is the reference's ambient
// visibility at the accuracy test's settings (tests/runtime/ao_accuracy_test.cpp:
// 512 rays at least, standard error 0.006), over the same pixels: the
// viewport, where the rasteriser and the ray tracer see the same surface.
// Prints MAE and bias of the raw estimate and of the blurred one.
#include "bench_harness.hpp"
#include "ao_thick_sectors.h"
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/reference.hpp"
#include "study_headers.hpp"

#include <spiral/optimizer.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

struct Error {
    double mae = 0.0, bias = 0.0;
};

Error measure(const deepgi::FloatImage& estimate, const deepgi::FloatImage& raster_depth,
              const deepgi::ReferenceImages& truth, int guard) {
    double sum_abs = 0.0, sum = 0.0;
    long long pixels = 0;
    const deepgi::FloatImage& traced = truth.depth_layer0;
    for (int y = guard; y < traced.height - guard; ++y) {
        for (int x = guard; x < traced.width - guard; ++x) {
            const float a = raster_depth.at(x, y), b = traced.at(x, y);
            if (!(a > 0.0f && b > 0.0f && std::abs(a - b) <= 1e-3f * b)) continue;
            const double e = double(std::clamp(estimate.at(x, y), 0.0f, 1.0f)) -
                             double(truth.ambient_visibility.at(x, y));
            sum_abs += std::abs(e);
            sum += e;
            ++pixels;
        }
    }
    if (pixels == 0) return {};
    return {sum_abs / double(pixels), sum / double(pixels)};
}

}  // namespace

int main(int argc, char** argv) {
    std::string size = "320x180";
    std::vector<std::string> scenes = {"ref-crease", "cornell", "warehouse", "atrium"};
    std::vector<int> tap_counts = {8, 11, 16, 24, 32};
    std::vector<int> sector_counts = {0, 2};
    CLI::App app{"thick_sector_study: thick spiral error per tap and sector count"};
    app.add_option("--size", size, "WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--scenes", scenes, "Scenes, comma-separated")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--taps", tap_counts, "Tap counts N, comma-separated")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--sectors", sector_counts,
                   "Sector counts S (1 to 8; 0: the shader's count for N), comma-separated")
        ->delimiter(',')
        ->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    return deepgi::bench::run("thick_sector_study", [&] {
        const auto [width, height] = deepgi::parse_size("--size", size);
        for (int s : sector_counts) {
            if (s < 0 || s > 8) throw deepgi::InputError("--sectors must be within 0 to 8");
        }
        for (int n : tap_counts) {
            if (n < 1 || n > 256) throw deepgi::InputError("--taps must be within 1 to 256");
        }
        deepgi::HeadlessContext context;
        const deepgi::study::ScratchFolder headers;
        const deepgi::ShaderLoader loader = deepgi::study::loader_with_override(headers.path());
        deepgi::RenderSettings settings;
        settings.width = width;
        settings.height = height;
        settings.shadow_map_size = 64;
        settings.ao.method = deepgi::AoMethod::spiral_thick;
        settings.ao.bias = deepgi::default_ao_bias(deepgi::AoMethod::spiral_thick);
        const int guard = deepgi::frame_layout(settings).guard;
        fmt::print("| scene | N | S | raw MAE | raw bias | blurred MAE | blurred bias |\n");
        fmt::print("|---|---|---|---|---|---|---|\n");
        for (const std::string& name : scenes) {
            const deepgi::Scene scene = deepgi::load_scene(name);
            deepgi::ReferenceSettings reference;
            reference.render = settings;
            reference.rays.min_rays = 512;
            reference.rays.target_error = 0.006;
            reference.threads = 2;
            const deepgi::ReferenceImages truth =
                deepgi::render_reference(deepgi::RayScene(scene), scene.default_camera, reference);
            for (int n : tap_counts) {
                const auto taps = spiral::codegen::spiral_taps(n, spiral::search(n).tau);
                for (int s : sector_counts) {
                    std::string header = deepgi::study::format_ao_header(
                        taps, spiral::search(n).tau, "thick_sector_study");
                    if (s > 0) header += fmt::format("#define AO_THICK_SECTORS {}\n", s);
                    spiral::codegen::write_file_atomically(headers.path() / "ao_taps.glsl", header);
                    deepgi::Renderer renderer(scene, settings, loader);
                    renderer.render(scene.default_camera);
                    const deepgi::FloatImage depth =
                        renderer.read_pass_output("gbuffer-depth-layer0");
                    const Error raw =
                        measure(renderer.read_pass_output("ao-raw"), depth, truth, guard);
                    const Error blurred =
                        measure(renderer.read_pass_output("ao-blurred"), depth, truth, guard);
                    fmt::print("| {} | {} | {} | {:.4f} | {:+.4f} | {:.4f} | {:+.4f} |\n", name, n,
                               s > 0 ? fmt::format("{}", s)
                                     : fmt::format("{} (own)", DEEPGI_AO_THICK_SECTORS_FOR(n)),
                               raw.mae, raw.bias, blurred.mae, blurred.bias);
                    std::fflush(stdout);
                }
            }
        }
        return 0;
    });
}
