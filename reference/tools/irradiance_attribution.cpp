// deepgi_irradiance_attribution DUMP_DIR REFERENCE_DIR SCENE [--radius R|auto] [--layers L]
//                               [--guard-band F] [--repeat DUMP_DIR2] [--maps DIR]
//                               [--view-band LO,HI]
// Where deep radiosity's error against the visible truth comes from
// (docs/radiosity-studies.md, "Where the error against the visible truth
// comes from"). From the dumped G-buffer it integrates, per viewport pixel X, what
// the stored surfaces send to X, exactly: every level-0 pixel p of the
// gathered layers as the planar patch the gather takes it for (solid angle
// s^2 z_p^2 cos(phi) cos_y / (|v|^2 max(cos(view), 0.1)), facing and radius
// tests as the gather's), with no taps, MIP levels, frames or clamp:
//   buffer, traced light  layer 0's light from the ray tracer's direct
//                         radiance (plus the G-buffer's emission), layer 1's
//                         the prepared radiance B;
//   buffer, exact view    every stored pixel within the radius in 3D, light
//                         B, without the max(cos(view), 0.1) bound;
//   buffer, all           the same with the bound, as the gather;
//   buffer, disk          only those within the screen disk of R = r / (s
//                         z_X) pixels around X, the area the taps sweep.
// Against the visible truth T (E0 + E1, or E0 with --layers 1) these and the
// renderer's filtered (radiosity-irradiance-layer0) and blurred E
// (radiosity-blurred) make a chain: T -> traced light (the buffer's
// resolution) -> all (the rasterised light) -> disk (what the screen disk
// does not reach) -> filtered (the taps after the frames: noise, MIP
// levels, clamp) -> blurred (the blur). With --repeat, a second dump of the
// same configuration with another temporal offset: the noise of one run is
// half the mean square of their difference, and the two runs' mean is
// measured too. Regions of X: silhouettes (a depth step within 2 pixels of
// layer 0), creases (a normal step within 2 pixels), near (the nearest
// stored point that sends X light within 4 pixels' footprint at X's depth)
// and the rest; each row gives each region's sum |E - T| and sum (E - T)
// over the whole T's sum, so the regions add up to the row. The truth's own
// noise comes from its standard-error image. With --maps, per-pixel error
// maps (E - T) / mean(T) as PNG (red: too bright, blue: too dark, full at
// 0.5; grey: not compared; 3x nearest-neighbour upscaling) and PFM, plus
// the region mask. MAE and bias as deepgi_compare_irradiance_split: sum |E -
// T| / sum T, channels summed. With --view-band LO,HI the four buffer
// integrals keep only the stored pixels p with LO <= cos(view) < HI (the
// G-buffer normal against the direction to the eye; the regions are
// unchanged): 1 + such a row's bias is the share of T that the band's
// stored pixels send.
#include "deepgi/image_io.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/settings.hpp"
#include "dump_frame.hpp"
#include "tool_arguments.hpp"

#include <fmt/format.h>
#include <glm/glm.hpp>

#include <algorithm>
#include <charconv>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct Options {
    float radius = deepgi::auto_length;
    float guard_band = deepgi::RenderSettings{}.guard_band_fraction;
    int layers = 2;
    std::optional<fs::path> repeat, maps;
    // --view-band: the buffer integrals' stored pixels, lo <= cos(view) < hi.
    std::optional<std::array<double, 2>> view_band;
};

// One layer of the dump, as the gather reads it at level 0.
struct Layer {
    deepgi::FloatImage depth, normal, radiance;
};

glm::vec3 rgb(const deepgi::FloatImage& image, int x, int y) {
    return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}

struct BufferSums {
    glm::dvec3 all{0.0}, disk{0.0}, exact_view{0.0}, traced_light{0.0};
    double nearest = 1e30;  // distance to the nearest stored point that sends X light
};

enum Region { silhouette = 0, crease = 1, near = 2, rest = 3, region_count = 4 };
constexpr const char* region_names[region_count] = {"silhouettes", "creases", "near", "rest"};

// Per stage and region: sum |E - T|, sum (E - T) over pixels and channels.
struct Tally {
    std::array<double, region_count> abs{}, signed_sum{};
};

void write_map(const fs::path& directory, const std::string& name, const deepgi::FloatImage& error,
               const std::vector<char>& compared) {
    deepgi::write_pfm(directory / (name + ".pfm"), error);
    constexpr int scale = 3;
    const int w = error.width, h = error.height;
    std::vector<std::uint8_t> rgba(std::size_t(w * scale) * h * scale * 4, 0);
    for (int y = 0; y < h * scale; ++y)
        for (int x = 0; x < w * scale; ++x) {
            const std::size_t i = (std::size_t(y) * w * scale + x) * 4;
            rgba[i + 3] = 255;
            const int sx = x / scale, sy = y / scale;
            if (!compared[std::size_t(sy) * w + sx]) {
                rgba[i] = rgba[i + 1] = rgba[i + 2] = 40;  // not compared: dark grey
                continue;
            }
            const float e = error.at(sx, sy);
            // Full colour at |e| = 0.5 of the truth's mean; white at 0.
            const float t = std::min(std::abs(e) / 0.5f, 1.0f);
            const auto fade = std::uint8_t(std::lround(255.0f * (1.0f - t)));
            rgba[i] = e > 0.0f ? 255 : fade;
            rgba[i + 1] = fade;
            rgba[i + 2] = e > 0.0f ? fade : 255;
        }
    deepgi::write_png(directory / (name + ".png"), w * scale, h * scale, rgba);
}

int run(int argc, char** argv) {
    CLI::App app{
        "Where deep radiosity's error against the visible truth comes from: the stored "
        "surfaces' exact integral, the screen disk, the taps, the blur (docs/radiosity.md)",
        "deepgi_irradiance_attribution"};
    deepgi_tools::use_tool_layout(app);
    fs::path dump, reference, repeat, maps;
    std::string scene_name, radius_text = "auto";
    Options options;
    deepgi_tools::add_dump_dir(app, dump);
    deepgi_tools::add_reference_dir(app, reference);
    deepgi_tools::add_scene(app, scene_name);
    app.add_option("--radius", radius_text,
                   "The gather radius in scene units, or auto as deepgi --radiosity-radius")
        ->check(CLI::Validator(
            [](const std::string& text) -> std::string {
                if (text == "auto") return "";
                float value = 0.0f;
                const auto [end, error] =
                    std::from_chars(text.data(), text.data() + text.size(), value);
                if (error != std::errc() || end != text.data() + text.size() || !(value > 0.0f) ||
                    !std::isfinite(value))
                    return "must be a finite number > 0, or auto";
                return "";
            },
            "R|auto"))
        ->capture_default_str();
    app.add_option("--layers", options.layers, "The G-buffer layers of the visible truth (1 or 2)")
        ->check(CLI::Range(1, 2))
        ->capture_default_str();
    deepgi_tools::add_guard_band(app, options.guard_band);
    app.add_option("--repeat", repeat,
                   "A second dump of the same configuration with another temporal offset")
        ->check(CLI::ExistingDirectory);
    app.add_option("--maps", maps, "A folder for the error maps (PNG and PFM)");
    app.add_option_function<std::string>(
           "--view-band",
           [&](const std::string& text) {
               // Read as doubles: the bounds compare with a double cos(view).
               const auto band = deepgi_tools::comma_numbers<double>(text, 2);
               if (!band || !std::isfinite((*band)[0]) || !std::isfinite((*band)[1]) ||
                   !((*band)[0] < (*band)[1]))
                   throw CLI::ValidationError("--view-band",
                                              "takes LO,HI, finite numbers with LO < HI");
               options.view_band = std::array<double, 2>{(*band)[0], (*band)[1]};
           },
           "The buffer integrals only over the stored pixels with LO <= cos(view) < HI (LO,HI)")
        ->default_str("every stored pixel");
    if (const auto status = deepgi_tools::parse(app, argc, argv)) return *status;
    if (radius_text != "auto") options.radius = std::stof(radius_text);
    if (!repeat.empty()) options.repeat = repeat;
    if (!maps.empty()) options.maps = maps;

    std::array<Layer, 2> layers;
    for (int j = 0; j < 2; ++j) {
        layers[j].depth = deepgi::read_pfm(dump / fmt::format("gbuffer-depth-layer{}.pfm", j));
        layers[j].normal = deepgi::read_pfm(dump / fmt::format("gbuffer-normal-layer{}.pfm", j));
        layers[j].radiance = deepgi::read_pfm(
            dump / fmt::format("radiosity_prepare-radiance-layer{}-level0.pfm", j));
    }
    const int w = layers[0].depth.width, h = layers[0].depth.height;
    const auto traced = deepgi::read_pfm(reference / "reference-depth-layer0.pfm");
    const auto part0 = deepgi::read_pfm(reference / "reference-irradiance-layer0.pfm");
    const auto part1 = deepgi::read_pfm(reference / "reference-irradiance-layer1.pfm");
    const auto traced_direct = deepgi::read_pfm(reference / "reference-direct-radiance.pfm");
    const auto emissive = deepgi::read_pfm(dump / "gbuffer-emissive-layer0.pfm");
    const auto standard_error =
        deepgi::read_pfm(reference / "reference-irradiance-standard-error.pfm");
    std::vector<deepgi::FloatImage> stages_e;
    std::vector<std::string> stage_names;
    auto add_stage = [&](const fs::path& directory, const char* file, const std::string& name) {
        stages_e.push_back(deepgi::read_pfm(directory / file));
        stage_names.push_back(name);
    };
    add_stage(dump, "radiosity-irradiance-layer0.pfm", "filtered");
    add_stage(dump, "radiosity-blurred.pfm", "blurred");
    if (options.repeat) {
        add_stage(*options.repeat, "radiosity-irradiance-layer0.pfm", "filtered, run 2");
        add_stage(*options.repeat, "radiosity-blurred.pfm", "blurred, run 2");
    }
    for (const deepgi::FloatImage* image :
         {&traced, &part0, &part1, static_cast<const deepgi::FloatImage*>(&layers[1].depth)})
        if (image->width != w || image->height != h)
            throw std::runtime_error("the dump and the reference differ in size");
    for (const auto& image : stages_e)
        if (image.width != w || image.height != h || image.channels != 3)
            throw std::runtime_error("a dumped E differs in size");

    const deepgi::Scene scene = deepgi::load_scene(scene_name);
    const deepgi::RenderSettings settings = deepgi_tools::with_scene_lengths(
        deepgi_tools::dump_viewport(w, h, options.guard_band), scene, options.radius);
    const auto layout = deepgi::frame_layout(settings);
    const float radius = settings.radiosity.radius;
    const double radius_squared = double(radius) * radius;
    const deepgi::Camera& camera = scene.default_camera;

    // Camera-space rays (z = -1) of every internal pixel centre.
    std::vector<glm::vec3> rays(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            rays[std::size_t(y) * w + x] =
                deepgi::camera_ray_direction(camera, settings, float(x) + 0.5f, float(y) + 0.5f);
    // Pixel side at unit depth: the ray's step from one row to the next.
    const double side = double(rays[std::size_t(1) * w].y - rays[0].y);

    // Stored points of the gathered layers, flattened once.
    struct Point {
        glm::dvec3 position, normal, radiance, traced;
        double area;  // s^2 z^2 cos(phi), over cos(view) below
        double cos_view;
        int x, y;
    };
    std::vector<Point> points;
    for (int j = 0; j < options.layers; ++j)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float z = layers[j].depth.at(x, y);
                if (!(z > 0.0f)) continue;
                Point p;
                const glm::dvec3 ray(rays[std::size_t(y) * w + x]);
                p.position = ray * double(z);
                p.normal = glm::dvec3(rgb(layers[j].normal, x, y));
                p.radiance = glm::dvec3(rgb(layers[j].radiance, x, y));
                // Layer 0 with the ray tracer's direct light (hard shadows,
                // no storage format) and the G-buffer's emission.
                p.traced =
                    j == 0 ? glm::dvec3(rgb(traced_direct, x, y)) + glm::dvec3(rgb(emissive, x, y))
                           : p.radiance;
                const double cos_phi = 1.0 / glm::length(ray);
                p.area = side * side * double(z) * z * cos_phi;
                p.cos_view = glm::dot(p.normal, -glm::normalize(p.position));
                p.x = x;
                p.y = y;
                if (p.radiance != glm::dvec3(0.0) || p.traced != glm::dvec3(0.0))
                    points.push_back(p);
            }

    std::vector<char> compared(std::size_t(w) * h, 0);
    std::vector<BufferSums> sums(std::size_t(w) * h);
    for (int y = layout.guard; y < h - layout.guard; ++y)
        for (int x = layout.guard; x < w - layout.guard; ++x) {
            const float a = layers[0].depth.at(x, y);
            if (!deepgi::same_surface_depth(a, traced.at(x, y))) continue;
            const std::size_t i = std::size_t(y) * w + x;
            compared[i] = 1;
            const glm::dvec3 position = glm::dvec3(rays[i]) * double(a);
            const glm::dvec3 normal(rgb(layers[0].normal, x, y));
            const double radius_pixels = double(radius) / (side * double(a));
            BufferSums& s = sums[i];
            for (const Point& p : points) {
                const glm::dvec3 v = p.position - position;
                const double vv = glm::dot(v, v);
                if (vv >= radius_squared || vv <= 0.0) continue;
                const glm::dvec3 d = v / std::sqrt(vv);
                const double cos_x = glm::dot(d, normal), cos_y = -glm::dot(d, p.normal);
                if (cos_x <= 0.0 || cos_y <= 0.0) continue;
                s.nearest = std::min(s.nearest, std::sqrt(vv));
                if (options.view_band &&
                    (p.cos_view < (*options.view_band)[0] || p.cos_view >= (*options.view_band)[1]))
                    continue;
                const double form = cos_x * cos_y * p.area / vv;
                const glm::dvec3 sent = p.radiance * form;
                s.traced_light += p.traced * (form / std::max(p.cos_view, 0.1));
                s.all += sent / std::max(p.cos_view, 0.1);
                s.exact_view += sent / std::max(p.cos_view, 1e-6);
                const double dx = p.x - x, dy = p.y - y;
                if (dx * dx + dy * dy < radius_pixels * radius_pixels)
                    s.disk += sent / std::max(p.cos_view, 0.1);
            }
        }

    // Regions: a silhouette (a step of over 5% in layer 0's depth, or its
    // edge on the background) within 2 pixels; else a crease (layer 0's
    // normal turns by more than acos 0.9) within 2 pixels; else near (the
    // nearest light-sending stored point within 4 pixels' footprint); else
    // the rest.
    auto step_at = [&](int x, int y, bool depth_step) {
        const float z = layers[0].depth.at(x, y);
        const glm::vec3 n = rgb(layers[0].normal, x, y);
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                const float nz = layers[0].depth.at(nx, ny);
                if (depth_step) {
                    if ((nz > 0.0f) != (z > 0.0f)) return true;
                    if (z > 0.0f && std::abs(nz - z) > 0.05f * z) return true;
                } else if (z > 0.0f && nz > 0.0f &&
                           glm::dot(rgb(layers[0].normal, nx, ny), n) < 0.9f) {
                    return true;
                }
            }
        return false;
    };
    std::array<std::vector<char>, 2> steps;
    for (int k = 0; k < 2; ++k) {
        steps[k].assign(std::size_t(w) * h, 0);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) steps[k][std::size_t(y) * w + x] = step_at(x, y, k == 0);
    }
    auto near_step = [&](int x, int y, int k) {
        for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if (nx >= 0 && ny >= 0 && nx < w && ny < h && steps[k][std::size_t(ny) * w + nx])
                    return true;
            }
        return false;
    };
    std::vector<int> region(std::size_t(w) * h, rest);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            if (!compared[i]) continue;
            const double footprint = side * double(layers[0].depth.at(x, y));
            if (near_step(x, y, 0))
                region[i] = silhouette;
            else if (near_step(x, y, 1))
                region[i] = crease;
            else if (sums[i].nearest < 4.0 * footprint)
                region[i] = near;
        }

    // Stages: the three buffer integrals, then the renderer's images.
    std::vector<std::string> names = {"buffer, traced light", "buffer, exact view", "buffer, all",
                                      "buffer, disk"};
    std::vector<std::function<glm::dvec3(int, int)>> stage;
    stage.push_back([&](int x, int y) { return sums[std::size_t(y) * w + x].traced_light; });
    stage.push_back([&](int x, int y) { return sums[std::size_t(y) * w + x].exact_view; });
    stage.push_back([&](int x, int y) { return sums[std::size_t(y) * w + x].all; });
    stage.push_back([&](int x, int y) { return sums[std::size_t(y) * w + x].disk; });
    for (std::size_t k = 0; k < stages_e.size(); ++k) {
        names.push_back(stage_names[k]);
        stage.push_back([&, k](int x, int y) { return glm::dvec3(rgb(stages_e[k], x, y)); });
    }
    if (options.repeat)
        for (int k = 0; k < 2; ++k) {
            names.push_back(k == 0 ? "filtered, mean of 2 runs" : "blurred, mean of 2 runs");
            stage.push_back([&, k](int x, int y) {
                return 0.5 * (glm::dvec3(rgb(stages_e[std::size_t(k)], x, y)) +
                              glm::dvec3(rgb(stages_e[std::size_t(k) + 2], x, y)));
            });
        }
    auto truth = [&](int x, int y) {
        glm::dvec3 t(rgb(part0, x, y));
        if (options.layers == 2) t += glm::dvec3(rgb(part1, x, y));
        return t;
    };

    std::array<double, region_count> truth_sum{};
    std::array<long long, region_count> count{};
    double total = 0.0;
    long long pixels = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            if (!compared[i]) continue;
            const glm::dvec3 t = truth(x, y);
            truth_sum[std::size_t(region[i])] += t.x + t.y + t.z;
            total += t.x + t.y + t.z;
            ++count[std::size_t(region[i])];
            ++pixels;
        }
    if (!(total > 0.0)) throw std::runtime_error("no visible light over the compared pixels");
    const double mean = total / (3.0 * double(pixels));

    fmt::print("{}: radius {:.3f}, {} layer(s), {} compared pixels, visible truth mean {:.4f}\n",
               scene_name, radius, options.layers, pixels, mean);
    if (options.view_band)
        fmt::print("buffer integrals over the stored pixels with {} <= cos(view) < {} only\n",
                   (*options.view_band)[0], (*options.view_band)[1]);
    // The truth's own noise: of the whole E's estimate (the split's parts
    // share its samples); E|N(0, s)| = s sqrt(2 / pi).
    double truth_noise = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (compared[std::size_t(y) * w + x])
                for (int c = 0; c < standard_error.channels; ++c)
                    truth_noise += standard_error.at(x, y, c) * std::sqrt(2.0 / 3.14159265358979) *
                                   (3.0 / standard_error.channels);
    fmt::print("the truth's own noise: mean |error| {:.3f} of its mean\n", truth_noise / total);
    fmt::print("regions (share of pixels / of the visible truth):");
    for (int r = 0; r < region_count; ++r)
        fmt::print(" {} {:.3f} / {:.3f};", region_names[r], double(count[r]) / double(pixels),
                   truth_sum[r] / total);
    fmt::print("\n\n| E | MAE | bias |");
    for (int r = 0; r < region_count; ++r) fmt::print(" MAE {0} | bias {0} |", region_names[r]);
    fmt::print("\n|---|--:|--:|");
    for (int r = 0; r < region_count; ++r) fmt::print("--:|--:|");
    fmt::print("\n");
    if (options.maps) fs::create_directories(*options.maps);
    for (std::size_t k = 0; k < stage.size(); ++k) {
        Tally tally;
        deepgi::FloatImage map{w, h, 1, std::vector<float>(std::size_t(w) * h, 0.0f)};
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t i = std::size_t(y) * w + x;
                if (!compared[i]) continue;
                const glm::dvec3 e = stage[k](x, y) - truth(x, y);
                const auto r = std::size_t(region[i]);
                tally.abs[r] += std::abs(e.x) + std::abs(e.y) + std::abs(e.z);
                tally.signed_sum[r] += e.x + e.y + e.z;
                map.pixels[i] = float((e.x + e.y + e.z) / (3.0 * mean));
            }
        double abs_all = 0.0, signed_all = 0.0;
        for (int r = 0; r < region_count; ++r) {
            abs_all += tally.abs[r];
            signed_all += tally.signed_sum[r];
        }
        fmt::print("| {} | {:.3f} | {:+.3f} |", names[k], abs_all / total, signed_all / total);
        for (int r = 0; r < region_count; ++r)
            fmt::print(" {:.3f} | {:+.3f} |", tally.abs[r] / total, tally.signed_sum[r] / total);
        fmt::print("\n");
        if (options.maps) {
            std::string file = names[k];
            std::replace(file.begin(), file.end(), ' ', '-');
            file.erase(std::remove(file.begin(), file.end(), ','), file.end());
            write_map(*options.maps, "error-" + file, map, compared);
        }
    }
    if (options.repeat) {
        // Var(run 1 - run 2) = 2 sigma^2 per pixel and channel.
        for (int k = 0; k < 2; ++k) {
            double square = 0.0, absolute = 0.0;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    if (!compared[std::size_t(y) * w + x]) continue;
                    const glm::dvec3 d = glm::dvec3(rgb(stages_e[std::size_t(k)], x, y)) -
                                         glm::dvec3(rgb(stages_e[std::size_t(k) + 2], x, y));
                    square += glm::dot(d, d);
                    absolute += std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
                }
            fmt::print(
                "{}: noise of one run, RMS {:.3f} and mean |run 1 - run 2| / sqrt(2) {:.3f} of the "
                "truth's mean\n",
                stage_names[std::size_t(k)], std::sqrt(square / (6.0 * double(pixels))) / mean,
                absolute / (3.0 * double(pixels)) / std::sqrt(2.0) / mean);
        }
    }
    if (options.maps) {
        deepgi::FloatImage mask{w, h, 1, std::vector<float>(std::size_t(w) * h, 0.0f)};
        std::vector<std::uint8_t> rgba(std::size_t(w) * h * 4, 0);
        constexpr std::uint8_t colours[region_count][3] = {
            {230, 60, 40}, {40, 140, 230}, {240, 200, 40}, {200, 200, 200}};
        for (std::size_t i = 0; i < compared.size(); ++i) {
            rgba[4 * i + 3] = 255;
            if (!compared[i]) continue;
            mask.pixels[i] = float(region[i] + 1);
            for (int c = 0; c < 3; ++c) rgba[4 * i + std::size_t(c)] = colours[region[i]][c];
        }
        deepgi::write_pfm(*options.maps / "regions.pfm", mask);
        deepgi::write_png(*options.maps / "regions.png", w, h, rgba);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return deepgi_tools::run_tool("deepgi_irradiance_attribution", argc, argv, run);
}
