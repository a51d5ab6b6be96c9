// deepgi_irradiance_region DUMP_DIR REFERENCE_DIR SCENE [--facing X,Y,Z] [--min-cos C]
//                          [--box X0,X1,Y0,Y1,Z0,Z1] [--toward R,G,B] [--guard-band F]
//                          [--sky-rays N] [--layers L]
// How much of its true indirect light a region of the image gets: over the
// viewport pixels where the traced and the dumped layer-0 depth agree, that
// emit nothing, whose world normal lies within acos(C) of the direction
// --facing (default 0,-1,0 and 0.9: ceilings) and, with --box, whose point
// lies in that world-space box, the sums of
//   E          the blurred irradiance compose reads (radiosity-blurred),
//   E + fill   the same plus the environment compose adds, env(n) (1 - c),
//   indirect   compose's radiance minus direct light and emission, over
//              albedo / pi (so E + fill, times the ambient visibility),
// each over the sum of the reference's E over the same pixels and channels
// (docs/radiosity-studies.md, "The cornell ceiling"); then the MAE and bias of E and
// of E + fill against that E, of E against the visible truth (E0 + E1, or
// E0 with --layers 1), and of E and E + fill against E + E_sky: the truth
// with the environment's irradiance through the gaps of the whole scene,
// which the reference's E leaves out and compose's fill also stands in for
// (traced here, --sky-rays cosine-weighted directions per pixel;
// "What recovers the missing share"). --min-cos -2 takes every pixel. With
// --toward, also the mean tint of E toward that colour, (e - 1/3) . (b -
// 1/3) / |b - 1/3| with e and b chromaticities (RGB over their sum), for the
// renderer's blurred and filtered E and the reference's E, E0, E0 + E1 and
// E1 (docs/radiosity-studies.md, "Atrium's blue banner"). DUMP_DIR and REFERENCE_DIR are
// deepgi --headless --dump and deepgi reference of the same scene and size.
#include "deepgi/image_io.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "dump_frame.hpp"
#include "tool_arguments.hpp"

#include <fmt/format.h>
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace {

constexpr float pi = 3.14159265358979f;

int run(int argc, char** argv) {
    CLI::App app{
        "A region's share of its true indirect light: the renderer's E, E + fill and "
        "indirect light against the ray-traced irradiance (docs/radiosity.md)",
        "deepgi_irradiance_region"};
    deepgi_tools::use_tool_layout(app);
    std::filesystem::path dump, reference;
    std::string scene_name;
    glm::vec3 facing(0.0f, -1.0f, 0.0f);
    int sky_rays = 256, layers = 2;
    float min_cos = 0.9f, guard_band = deepgi::RenderSettings{}.guard_band_fraction;
    float box[6] = {-1e30f, 1e30f, -1e30f, 1e30f, -1e30f, 1e30f};
    glm::vec3 toward(0.0f);
    deepgi_tools::add_dump_dir(app, dump);
    deepgi_tools::add_reference_dir(app, reference);
    deepgi_tools::add_scene(app, scene_name);
    app.add_option_function<std::string>(
           "--facing",
           [&](const std::string& text) {
               const auto v = deepgi_tools::comma_numbers(text, 3);
               if (!v || !(glm::length(glm::vec3((*v)[0], (*v)[1], (*v)[2])) > 0.0f))
                   throw CLI::ValidationError("--facing", "takes X,Y,Z, not all 0");
               facing = glm::normalize(glm::vec3((*v)[0], (*v)[1], (*v)[2]));
           },
           "The world direction the region's normals face (X,Y,Z)")
        ->default_str("0,-1,0: ceilings");
    app.add_option("--min-cos", min_cos,
                   "The least cosine between a pixel's normal and --facing (-2: every pixel)")
        ->capture_default_str();
    app.add_option_function<std::string>(
           "--box",
           [&](const std::string& text) {
               const auto v = deepgi_tools::comma_numbers(text, 6);
               if (!v) throw CLI::ValidationError("--box", "takes X0,X1,Y0,Y1,Z0,Z1");
               std::copy(v->begin(), v->end(), box);
           },
           "Only the points inside this world-space box (X0,X1,Y0,Y1,Z0,Z1)")
        ->default_str("everywhere");
    app.add_option_function<std::string>(
           "--toward",
           [&](const std::string& text) {
               const auto v = deepgi_tools::comma_numbers(text, 3);
               if (!v || !((*v)[0] + (*v)[1] + (*v)[2] > 0.0f))
                   throw CLI::ValidationError("--toward", "takes R,G,B with a positive sum");
               toward = glm::vec3((*v)[0], (*v)[1], (*v)[2]);
           },
           "Also the mean tint of E toward this colour (R,G,B)")
        ->default_str("no tint");
    deepgi_tools::add_guard_band(app, guard_band);
    app.add_option("--sky-rays", sky_rays,
                   "Cosine-weighted directions per pixel for the environment's irradiance E_sky")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--layers", layers, "The G-buffer layers of the visible truth (1 or 2)")
        ->check(CLI::Range(1, 2))
        ->capture_default_str();
    if (const auto status = deepgi_tools::parse(app, argc, argv)) return *status;
    auto read = [&](const std::filesystem::path& folder, const char* name) {
        return deepgi::read_pfm(folder / (std::string(name) + ".pfm"));
    };
    const auto raster = read(dump, "gbuffer-depth-layer0");
    const auto normal = read(dump, "gbuffer-normal-layer0");
    const auto albedo = read(dump, "gbuffer-albedo-layer0");
    const auto emissive = read(dump, "gbuffer-emissive-layer0");
    const auto direct = read(dump, "direct_light-radiance-layer0");
    const auto blurred = read(dump, "radiosity-blurred");
    const auto confidence = read(dump, "radiosity-blurred-confidence");
    const auto composed = read(dump, "compose-radiance");
    const auto traced = read(reference, "reference-depth-layer0");
    const auto truth = read(reference, "reference-irradiance");
    const auto part0 = read(reference, "reference-irradiance-layer0");
    const auto part1 = read(reference, "reference-irradiance-layer1");
    const auto filtered = read(dump, "radiosity-irradiance-layer0");
    const deepgi::RayScene rays(deepgi::load_scene(scene_name));
    const int w = raster.width, h = raster.height;
    if (truth.width != w || truth.height != h)
        throw std::runtime_error(fmt::format("size mismatch: dump {}x{}, reference {}x{}", w, h,
                                             truth.width, truth.height));
    const deepgi::Scene scene = deepgi::load_scene(scene_name);
    const deepgi::RenderSettings settings = deepgi_tools::dump_viewport(w, h, guard_band);
    const auto layout = deepgi::frame_layout(settings);
    // Camera-space normals to world space, as compose.frag does.
    const glm::mat4 view = deepgi::camera_view_matrix(scene.default_camera);
    const glm::mat3 to_world = glm::transpose(glm::mat3(view));
    const glm::mat4 camera_to_world = glm::inverse(view);
    const glm::vec3 eye(camera_to_world[3]);
    // The environment's irradiance at X through the gaps of the whole scene:
    // cosine-weighted directions (stratified, jittered) that hit nothing at
    // any distance see the environment's radiance (RayScene's, as the
    // reflections see it). What the reference's E leaves out, and what
    // compose's fill stands in for besides the light no layer holds.
    std::uint64_t state = 0x9E3779B97F4A7C15ull;
    auto uniform = [&state] {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return double(z ^ (z >> 31)) * (1.0 / 18446744073709551616.0);
    };
    auto sky_irradiance = [&](int x, int y) {
        const glm::vec3 ray = glm::vec3(
            camera_to_world * glm::vec4(deepgi::camera_ray_direction(scene.default_camera, settings,
                                                                     x + 0.5f, y + 0.5f),
                                        0.0f));
        const deepgi::RayScene::Hit hit =
            rays.intersect_front(eye, ray, scene.default_camera.near_plane, 1e30f);
        glm::dvec3 sum(0.0);
        if (!hit.hit) return sum;
        const glm::vec3 p = eye + ray * hit.distance;
        const glm::dvec3 n(hit.normal);
        const double sign = std::copysign(1.0, n.z), a = -1.0 / (sign + n.z), c = n.x * n.y * a;
        const glm::dvec3 t(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
        const glm::dvec3 b(c, sign + n.y * n.y * a, -n.y);
        const glm::vec3 origin =
            p +
            hit.normal * (1e-5f * std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) + 1e-4f);
        for (int k = 0; k < sky_rays; ++k) {
            const double u1 = (k + uniform()) / sky_rays, u2 = uniform();
            const double s = std::sqrt(u1), phi = 2.0 * double(pi) * u2;
            const glm::vec3 w(t * (s * std::cos(phi)) + b * (s * std::sin(phi)) +
                              n * std::sqrt(std::max(0.0, 1.0 - u1)));
            if (!rays.occluded(origin, w, 0.0f, 1e30f)) sum += rays.environment_radiance(w);
        }
        return sum * (double(pi) / sky_rays);
    };
    // Tint of an RGB irradiance toward `toward` (0 for black).
    const glm::dvec3 target = glm::dvec3(toward) / double(toward.x + toward.y + toward.z);
    const glm::dvec3 direction = glm::length(target - 1.0 / 3.0) > 0.0
                                     ? glm::normalize(target - 1.0 / 3.0)
                                     : glm::dvec3(0.0);
    auto tint = [&](const deepgi::FloatImage& image, int x, int y, const deepgi::FloatImage* plus) {
        glm::dvec3 e(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2));
        if (plus) e += glm::dvec3(plus->at(x, y, 0), plus->at(x, y, 1), plus->at(x, y, 2));
        const double total = e.x + e.y + e.z;
        return total > 0.0 ? glm::dot(e / total - 1.0 / 3.0, direction) : 0.0;
    };
    double tints[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    double abs_e_sky = 0.0;
    // environment_irradiance() as environment.glsl: the constant ambient
    // under a black background, the analytic sky otherwise.
    const glm::vec3 ambient = scene.ambient, background = scene.background;
    const bool sky = background != glm::vec3(0.0f);
    auto environment = [&](glm::vec3 n) {
        if (!sky) return pi * ambient;
        return pi * glm::mix(ambient * 0.5f, ambient + background * 0.25f, 0.5f + 0.5f * n.y);
    };
    double sum_truth = 0.0, sum_e = 0.0, sum_filled = 0.0, sum_indirect = 0.0;
    double sum_seen = 0.0, sum_sky = 0.0, abs_filled_sky = 0.0, abs_e = 0.0, abs_filled = 0.0,
           abs_e_seen = 0.0;
    long long count = 0;
    for (int y = layout.guard; y < h - layout.guard; ++y)
        for (int x = layout.guard; x < w - layout.guard; ++x) {
            const float a = raster.at(x, y);
            if (!deepgi::same_surface_depth(a, traced.at(x, y))) continue;
            const glm::vec3 n = glm::normalize(
                to_world * glm::vec3(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2)));
            if (glm::dot(n, facing) < min_cos) continue;
            const glm::vec3 p =
                glm::vec3(camera_to_world *
                          glm::vec4(deepgi::camera_ray_direction(scene.default_camera, settings,
                                                                 x + 0.5f, y + 0.5f) *
                                        a,
                                    1.0f));
            if (p.x < box[0] || p.x > box[1] || p.y < box[2] || p.y > box[3] || p.z < box[4] ||
                p.z > box[5])
                continue;
            tints[0] += tint(blurred, x, y, nullptr);
            tints[1] += tint(filtered, x, y, nullptr);
            tints[2] += tint(truth, x, y, nullptr);
            tints[3] += tint(part0, x, y, nullptr);
            tints[4] += tint(part0, x, y, &part1);
            tints[5] += tint(part1, x, y, nullptr);
            if (emissive.at(x, y, 0) + emissive.at(x, y, 1) + emissive.at(x, y, 2) > 0.0f) continue;
            const glm::vec3 env = environment(n);
            const float c = std::clamp(confidence.at(x, y), 0.0f, 1.0f);
            const glm::dvec3 sky = sky_irradiance(x, y);
            for (int k = 0; k < 3; ++k) {
                const double t = truth.at(x, y, k), e = blurred.at(x, y, k);
                const double seen =
                    double(part0.at(x, y, k)) + (layers == 2 ? part1.at(x, y, k) : 0.0f);
                const double filled = e + env[k] * (1.0f - c);
                sum_truth += t;
                sum_seen += seen;
                sum_e += e;
                sum_filled += filled;
                abs_e += std::abs(e - t);
                abs_filled += std::abs(filled - t);
                abs_e_seen += std::abs(e - seen);
                sum_sky += sky[k];
                abs_filled_sky += std::abs(filled - t - sky[k]);
                abs_e_sky += std::abs(e - t - sky[k]);
                const double rho = albedo.at(x, y, k);
                if (rho > 0.0)
                    sum_indirect +=
                        (composed.at(x, y, k) - direct.at(x, y, k) - emissive.at(x, y, k)) * pi /
                        rho;
            }
            ++count;
        }
    if (count == 0 || !(sum_truth > 0.0)) throw std::runtime_error("no lit pixel in the region");
    fmt::print(
        "{} pixels facing ({:.2f}, {:.2f}, {:.2f}); reference mean E {:.4f}; against it: E {:.3f}, "
        "E + fill {:.3f}, composed indirect {:.3f}\n",
        count, facing.x, facing.y, facing.z, sum_truth / (3.0 * count), sum_e / sum_truth,
        sum_filled / sum_truth, sum_indirect / sum_truth);
    fmt::print(
        "against the whole truth: E MAE {:.3f} bias {:+.3f}; E + fill MAE {:.3f} bias {:+.3f}; "
        "against the visible truth ({}, {:.3f} of E): E MAE {:.3f} bias {:+.3f}\n",
        abs_e / sum_truth, sum_e / sum_truth - 1.0, abs_filled / sum_truth,
        sum_filled / sum_truth - 1.0, layers == 2 ? "E0 + E1" : "E0", sum_seen / sum_truth,
        abs_e_seen / sum_seen, sum_e / sum_seen - 1.0);
    fmt::print(
        "against the truth with the environment seen through the scene, E + E_sky (E_sky {:.3f} "
        "of E): E MAE {:.3f} bias {:+.3f}; E + fill MAE {:.3f} bias {:+.3f}\n",
        sum_sky / sum_truth, abs_e_sky / (sum_truth + sum_sky),
        (sum_e - sum_truth - sum_sky) / (sum_truth + sum_sky),
        abs_filled_sky / (sum_truth + sum_sky),
        (sum_filled - sum_truth - sum_sky) / (sum_truth + sum_sky));
    if (toward != glm::vec3(0.0f))
        fmt::print(
            "tint toward ({:.2f}, {:.2f}, {:.2f}): renderer blurred {:+.4f}, filtered {:+.4f}; "
            "reference E {:+.4f}, E0 {:+.4f}, E0 + E1 {:+.4f}, E1 {:+.4f}\n",
            toward.x, toward.y, toward.z, tints[0] / count, tints[1] / count, tints[2] / count,
            tints[3] / count, tints[4] / count, tints[5] / count);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return deepgi_tools::run_tool("deepgi_irradiance_region", argc, argv, run);
}
