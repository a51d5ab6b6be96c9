// deepgi_irradiance_unoccluded_study DUMP_DIR SCENE [--radius R] [--layers L]
//                                    [--rays N] [--stride S] [--threads T] [--guard-band F]
//                                    [--view-bands E1,E2,...]
//                                    [--write-truth DIR --reference REFERENCE_DIR]
// What a gather over the layers converges to when, like deep radiosity's,
// it tests no visibility between the pixel X and the surface Y it reads.
// The reference (docs/reference.md) traces each direction to its first
// surface; the gather instead sums every surface point the layers hold
// within the radius that faces X, whether or not something lies between.
// Along each cosine-weighted direction from X this walks every surface
// within the radius and sums the outgoing radiance L(y) of each front face
// a layer holds (layer_classifier()), so
//     E_unoccluded(X) = pi * mean over directions of sum_y L(y)
// is the integral the gather estimates, and E_visible(X) (the first
// surface only, when a layer holds it) the visible truth, from the same
// directions. Over the viewport where the traced and the dumped layer-0
// depth agree, prints both against the dumped E (DUMP_DIR from deepgi
// --headless --dump with the same scene, size, radius and layer count):
// the share of E_unoccluded that hidden surfaces add, and the relative bias
// of E against each (docs/radiosity-studies.md, "Why warehouse finds more
// light than its layers hold").
// --view-bands E1,E2,... (increasing) also prints the share of E_unoccluded
// sent by surfaces in each band of cos(view_Y) these edges bound, below E1,
// from E1 to E2, ..., from the last up: view_Y is the direction from Y to
// the eye, against the traced surface's geometric normal.
// --write-truth DIR --reference REFERENCE_DIR writes E_unoccluded as a
// reference folder, for deepgi_irradiance_attribution DUMP_DIR DIR SCENE to
// measure its chain against it: REFERENCE_DIR (deepgi reference, the dump's
// scene, size and guard band) gives its depth layers, direct radiance and
// standard error, copied as they are; E_unoccluded of every compared pixel
// becomes reference-irradiance-layer0.pfm (0 where not compared) and
// reference-irradiance-layer1.pfm is 0, so that E0 + E1 is E_unoccluded.
// It needs --stride 1: a reference holds every pixel.
#include "deepgi/image_io.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/settings.hpp"
#include "dump_frame.hpp"
#include "tool_arguments.hpp"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

namespace {

constexpr double pi = 3.14159265358979323846;

struct Options {
    float radius = deepgi::auto_length;
    float guard_band = deepgi::RenderSettings{}.guard_band_fraction;
    int layers = 2, rays = 256, stride = 2, threads = 1;
    std::vector<float> view_edges;  // --view-bands, increasing; none: no bands
    std::filesystem::path write_truth, reference;
};

// Per pixel: the unoccluded and the visible sums (RGB), and the part of the
// unoccluded sum whose surface is not the first one along its direction;
// with --view-bands, the unoccluded sum (channels summed, unscaled) by band
// of cos(view_Y).
struct PixelSums {
    glm::dvec3 unoccluded{0.0}, visible{0.0}, hidden{0.0};
    std::vector<double> by_view;
};

struct Random {
    std::uint64_t state;
    double next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return double(z ^ (z >> 31)) * (1.0 / 18446744073709551616.0);
    }
};

float surface_offset(glm::vec3 p, float length) {
    return 1e-5f * std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) + 1e-6f * length;
}

PixelSums trace_pixel(const deepgi::RayScene& scene, const deepgi::LayerClassifier& classify,
                      glm::vec3 position, glm::vec3 normal, float radius, int layers, int rays,
                      std::uint64_t seed, glm::vec3 eye, const std::vector<float>& view_edges) {
    const glm::dvec3 n(normal);
    // Tangent frame (Duff et al.).
    const double sign = std::copysign(1.0, n.z), a = -1.0 / (sign + n.z), c = n.x * n.y * a;
    const glm::dvec3 t(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
    const glm::dvec3 b(c, sign + n.y * n.y * a, -n.y);
    const glm::vec3 origin = position + normal * surface_offset(position, radius);
    Random random{seed};
    PixelSums sums;
    if (!view_edges.empty()) sums.by_view.assign(view_edges.size() + 1, 0.0);
    for (int k = 0; k < rays; ++k) {
        // Stratified in the squared disk radius, jittered: cosine-weighted.
        const double u1 = (k + random.next()) / rays, u2 = random.next();
        const double s = std::sqrt(u1), phi = 2.0 * pi * u2, z = std::sqrt(std::max(0.0, 1.0 - u1));
        const glm::vec3 w(t * (s * std::cos(phi)) + b * (s * std::sin(phi)) + n * z);
        float near = 0.0f;
        bool first = true;
        // Every surface along w within the radius (a cap keeps degenerate
        // stacks of coplanar triangles finite).
        for (int hits = 0; hits < 256; ++hits) {
            const deepgi::RayScene::Hit hit = scene.intersect(origin, w, near, radius);
            if (!hit.hit) break;
            const glm::vec3 y = origin + w * hit.distance;
            near = hit.distance + std::max(1e-5f * hit.distance, surface_offset(y, radius));
            const bool facing = glm::dot(hit.normal, w) < 0.0f;
            const int layer = facing ? classify(y) : -1;
            if (layer >= 0 && layer < layers) {
                const glm::dvec3 radiance = deepgi::direct_outgoing_radiance(scene, hit, y);
                sums.unoccluded += radiance;
                if (!view_edges.empty()) {
                    const float cos_view = glm::dot(hit.normal, glm::normalize(eye - y));
                    std::size_t band = 0;
                    while (band < view_edges.size() && cos_view >= view_edges[band]) ++band;
                    sums.by_view[band] += radiance.x + radiance.y + radiance.z;
                }
                if (first)
                    sums.visible += radiance;
                else
                    sums.hidden += radiance;
            }
            first = false;
        }
    }
    const double scale = pi / rays;
    sums.unoccluded *= scale;
    sums.visible *= scale;
    sums.hidden *= scale;
    return sums;
}

// --write-truth: the unoccluded light as a reference folder (see the top).
void write_truth_folder(const Options& options, const std::vector<PixelSums>& sums,
                        const std::vector<char>& compared, int w, int h) {
    namespace fs = std::filesystem;
    const auto depth = deepgi::read_pfm(options.reference / "reference-depth-layer0.pfm");
    if (depth.width != w || depth.height != h)
        throw std::runtime_error("the dump and the reference differ in size");
    fs::create_directories(options.write_truth);
    for (const char* file :
         {"reference-depth-layer0.pfm", "reference-depth-layer1.pfm",
          "reference-direct-radiance.pfm", "reference-irradiance-standard-error.pfm"})
        fs::copy_file(options.reference / file, options.write_truth / file,
                      fs::copy_options::overwrite_existing);
    deepgi::FloatImage unoccluded{w, h, 3, std::vector<float>(std::size_t(w) * h * 3, 0.0f)};
    const deepgi::FloatImage zero = unoccluded;
    for (std::size_t i = 0; i < sums.size(); ++i)
        if (compared[i])
            for (int c = 0; c < 3; ++c)
                unoccluded.pixels[i * 3 + std::size_t(c)] = float(sums[i].unoccluded[c]);
    deepgi::write_pfm(options.write_truth / "reference-irradiance-layer0.pfm", unoccluded);
    deepgi::write_pfm(options.write_truth / "reference-irradiance-layer1.pfm", zero);
}

int run(int argc, char** argv) {
    CLI::App app{
        "What a gather without a visibility test converges to: every surface the "
        "layers hold within the radius, against the dump's E (docs/radiosity.md)",
        "deepgi_irradiance_unoccluded_study"};
    deepgi_tools::use_tool_layout(app);
    std::filesystem::path dump;
    std::string scene_name;
    Options options;
    deepgi_tools::add_dump_dir(app, dump);
    deepgi_tools::add_scene(app, scene_name);
    app.add_option_function<std::string>(
           "--radius",
           [&](const std::string& text) {
               if (text == "auto") {
                   options.radius = deepgi::auto_length;
                   return;
               }
               const auto value = deepgi_tools::comma_numbers(text, 1);
               if (!value || !((*value)[0] > 0.0f))
                   throw CLI::ValidationError("--radius", "must be a number > 0 or auto");
               options.radius = (*value)[0];
           },
           "The gather's radius in metres, or auto as the renderer picks it")
        ->default_str("auto");
    deepgi_tools::add_guard_band(app, options.guard_band);
    app.add_option("--layers", options.layers, "The G-buffer layers the gather reads (1 or 2)")
        ->check(CLI::Range(1, 2))
        ->capture_default_str();
    app.add_option("--rays", options.rays, "Cosine-weighted directions per pixel")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--stride", options.stride, "Every stride-th pixel in x and y")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--threads", options.threads, "Worker threads")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option_function<std::string>(
           "--view-bands",
           [&](const std::string& text) {
               const auto edges = deepgi_tools::comma_numbers(
                   text, std::size_t(std::count(text.begin(), text.end(), ',')) + 1);
               const auto finite = [](float e) { return std::isfinite(e); };
               const auto not_increasing = [](float a, float b) { return !(a < b); };
               if (!edges || !std::all_of(edges->begin(), edges->end(), finite) ||
                   std::adjacent_find(edges->begin(), edges->end(), not_increasing) != edges->end())
                   throw CLI::ValidationError("--view-bands",
                                              "takes finite edges E1,E2,... in increasing order");
               options.view_edges = *edges;
           },
           "Also the share of the unoccluded light by band of cos(view_Y) between these edges "
           "(E1,E2,...)")
        ->default_str("no bands");
    auto* write_truth =
        app.add_option("--write-truth", options.write_truth,
                       "Write the unoccluded light as a reference folder (needs --reference and "
                       "--stride 1)");
    auto* reference =
        app.add_option("--reference", options.reference,
                       "The folder deepgi reference wrote for the dump, whose depth, direct "
                       "radiance and standard error --write-truth copies")
            ->check(CLI::ExistingDirectory);
    write_truth->needs(reference);
    reference->needs(write_truth);
    app.callback([&] {
        if (options.write_truth.empty()) return;
        if (options.stride != 1)
            throw CLI::ValidationError("--write-truth",
                                       "needs --stride 1: a reference holds every pixel");
        std::error_code error;
        if (std::filesystem::equivalent(options.write_truth, options.reference, error))
            throw CLI::ValidationError("--write-truth",
                                       "must not be the --reference folder it copies");
    });
    if (const auto status = deepgi_tools::parse(app, argc, argv)) return *status;

    const auto depth = deepgi::read_pfm(dump / "gbuffer-depth-layer0.pfm");
    const auto blurred = deepgi::read_pfm(dump / "radiosity-blurred.pfm");
    const auto filtered = deepgi::read_pfm(dump / "radiosity-irradiance-layer0.pfm");
    const int w = depth.width, h = depth.height;
    const deepgi::Scene scene = deepgi::load_scene(scene_name);
    const deepgi::RenderSettings settings = deepgi_tools::with_scene_lengths(
        deepgi_tools::dump_viewport(w, h, options.guard_band), scene, options.radius);
    const auto layout = deepgi::frame_layout(settings);
    const float radius = settings.radiosity.radius;

    const deepgi::RayScene rays(scene);
    const deepgi::Camera& camera = scene.default_camera;
    const deepgi::LayerClassifier classify = deepgi::layer_classifier(rays, camera, settings);
    const glm::mat4 camera_to_world = glm::inverse(deepgi::camera_view_matrix(camera));
    const glm::vec3 eye(camera_to_world[3]);

    std::vector<PixelSums> sums(std::size_t(w) * h);
    std::vector<char> compared(std::size_t(w) * h, 0);
    std::atomic<int> next_row{layout.guard};
    auto work = [&] {
        for (int y = next_row.fetch_add(options.stride); y < h - layout.guard;
             y = next_row.fetch_add(options.stride))
            for (int x = layout.guard; x < w - layout.guard; x += options.stride) {
                const glm::vec3 direction(
                    camera_to_world *
                    glm::vec4(deepgi::camera_ray_direction(camera, settings, x + 0.5f, y + 0.5f),
                              0.0f));
                const deepgi::RayScene::Hit hit =
                    rays.intersect_front(eye, direction, camera.near_plane, 1e30f);
                if (!hit.hit || !deepgi::same_surface_depth(depth.at(x, y), hit.distance)) continue;
                const std::size_t i = std::size_t(y) * w + x;
                compared[i] = 1;
                sums[i] = trace_pixel(rays, classify, eye + direction * hit.distance, hit.normal,
                                      radius, options.layers, options.rays,
                                      0x243F6A8885A308D3ull ^ (i * 0xD1B54A32D192ED03ull), eye,
                                      options.view_edges);
            }
    };
    std::vector<std::thread> workers;
    for (int i = 0; i < options.threads; ++i) workers.emplace_back(work);
    for (auto& worker : workers) worker.join();

    double unoccluded = 0.0, visible = 0.0, hidden = 0.0;
    double bias_unoccluded[2] = {0.0, 0.0}, bias_visible[2] = {0.0, 0.0};
    double abs_unoccluded[2] = {0.0, 0.0}, abs_visible[2] = {0.0, 0.0};
    long long count = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            if (!compared[i]) continue;
            ++count;
            for (int c = 0; c < 3; ++c) {
                unoccluded += sums[i].unoccluded[c];
                visible += sums[i].visible[c];
                hidden += sums[i].hidden[c];
                const double e[2] = {blurred.at(x, y, c), filtered.at(x, y, c)};
                for (int k = 0; k < 2; ++k) {
                    bias_unoccluded[k] += e[k] - sums[i].unoccluded[c];
                    bias_visible[k] += e[k] - sums[i].visible[c];
                    abs_unoccluded[k] += std::abs(e[k] - sums[i].unoccluded[c]);
                    abs_visible[k] += std::abs(e[k] - sums[i].visible[c]);
                }
            }
        }
    if (count == 0 || !(visible > 0.0))
        throw std::runtime_error("no light over the compared pixels");
    if (!options.write_truth.empty()) write_truth_folder(options, sums, compared, w, h);
    fmt::print("{}: radius {:.3f}, {} layer(s), {} pixels, {} directions each\n", scene_name,
               radius, options.layers, count, options.rays);
    fmt::print("unoccluded / visible {:.3f}; hidden surfaces' share of unoccluded {:.3f}\n",
               unoccluded / visible, hidden / unoccluded);
    const char* names[2] = {"radiosity-blurred", "radiosity-irradiance-layer0"};
    for (int k = 0; k < 2; ++k)
        fmt::print(
            "{}: against the visible layers MAE {:.3f}, bias {:+.3f}; against the unoccluded "
            "layers MAE {:.3f}, bias {:+.3f}\n",
            names[k], abs_visible[k] / visible, bias_visible[k] / visible,
            abs_unoccluded[k] / unoccluded, bias_unoccluded[k] / unoccluded);
    fmt::print("| {} | {:.2f} | {} | {:.3f} | {:.3f} | {:+.3f} | {:+.3f} |\n", scene_name, radius,
               options.layers, unoccluded / visible, hidden / unoccluded, bias_visible[0] / visible,
               bias_unoccluded[0] / unoccluded);
    if (!options.view_edges.empty()) {
        const std::vector<float>& edges = options.view_edges;
        std::vector<double> bands(edges.size() + 1, 0.0);
        double all = 0.0;
        for (std::size_t i = 0; i < sums.size(); ++i)
            if (compared[i])
                for (std::size_t b = 0; b < bands.size(); ++b) {
                    bands[b] += sums[i].by_view[b];
                    all += sums[i].by_view[b];
                }
        fmt::print("share of unoccluded by cos(view_Y): < {} {:.4f}", edges[0], bands[0] / all);
        for (std::size_t b = 1; b < edges.size(); ++b)
            fmt::print(", {} to {} {:.4f}", edges[b - 1], edges[b], bands[b] / all);
        fmt::print(", >= {} {:.4f}\n", edges.back(), bands.back() / all);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return deepgi_tools::run_tool("deepgi_irradiance_unoccluded_study", argc, argv, run);
}
