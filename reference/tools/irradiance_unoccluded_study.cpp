// deepgi_irradiance_unoccluded_study DUMP_DIR SCENE [--radius R] [--layers L]
//                                    [--rays N] [--stride S] [--threads T] [--guard-band F]
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
#include <thread>
#include <vector>

namespace {

constexpr double pi = 3.14159265358979323846;

struct Options {
    float radius = deepgi::auto_length;
    float guard_band = deepgi::RenderSettings{}.guard_band_fraction;
    int layers = 2, rays = 256, stride = 2, threads = 1;
};

// Per pixel: the unoccluded and the visible sums (RGB), and the part of the
// unoccluded sum whose surface is not the first one along its direction.
struct PixelSums {
    glm::dvec3 unoccluded{0.0}, visible{0.0}, hidden{0.0};
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
                      std::uint64_t seed) {
    const glm::dvec3 n(normal);
    // Tangent frame (Duff et al.).
    const double sign = std::copysign(1.0, n.z), a = -1.0 / (sign + n.z), c = n.x * n.y * a;
    const glm::dvec3 t(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
    const glm::dvec3 b(c, sign + n.y * n.y * a, -n.y);
    const glm::vec3 origin = position + normal * surface_offset(position, radius);
    Random random{seed};
    PixelSums sums;
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
                                      0x243F6A8885A308D3ull ^ (i * 0xD1B54A32D192ED03ull));
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
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return deepgi_tools::run_tool("deepgi_irradiance_unoccluded_study", argc, argv, run);
}
