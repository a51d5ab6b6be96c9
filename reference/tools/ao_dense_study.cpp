// deepgi_ao_dense_study DUMP_DIR REFERENCE_DIR SCENE [options]
// What the solid-angle estimator of deep SAO converges to when every pixel of
// the screen disk is a tap (no spiral, no MIP levels, no blur), against the
// ray-traced AV: it separates the estimator's formula and the G-buffer's
// reach from the sampling of the shader. Options switch single terms of the
// formula so each can be measured on its own (docs/deep-sao-studies.md).
#include "deepgi/image_io.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "dump_frame.hpp"
#include "tool_arguments.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

int run(int argc, char** argv) {
    CLI::App app{
        "What the solid-angle estimator converges to with every pixel of the disk a "
        "tap, against the ray-traced ambient visibility (docs/deep-sao-studies.md)",
        "deepgi_ao_dense_study"};
    deepgi_tools::use_tool_layout(app);
    std::filesystem::path dump, reference;
    std::string scene_name;
    float bias = 0.01f, footprint_factor = 0.5f, clamp_view = 0.1f, reach = 1.0f, radius = 0.5f;
    int subtract = 1, cos_phi = 0, sub = 1, layers = 2, stride = 3;
    deepgi_tools::add_dump_dir(app, dump);
    deepgi_tools::add_reference_dir(app, reference);
    deepgi_tools::add_scene(app, scene_name);
    app.add_option("--bias", bias, "The bias beta in metres")->capture_default_str();
    app.add_option("--footprint", footprint_factor,
                   "The footprint term of the bias, in pixel sizes at the pixel's depth")
        ->capture_default_str();
    app.add_option("--subtract", subtract,
                   "1: the bias is subtracted from v.n; 0: it only thresholds it")
        ->check(CLI::Range(0, 1))
        ->capture_default_str();
    app.add_option("--clamp", clamp_view,
                   "The least |cos| between a tap's normal and the view ray in its area")
        ->capture_default_str();
    app.add_option(
           "--cos-phi", cos_phi,
           "1: each tap's area is also scaled by the cosine of its view ray to the view axis")
        ->check(CLI::Range(0, 1))
        ->capture_default_str();
    app.add_option("--reach", reach, "The pixels searched, as a share of the radius")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--sub", sub, "Sub-pixel points per tap pixel along each axis")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--layers", layers, "The G-buffer layers read (1 or 2)")
        ->check(CLI::Range(1, 2))
        ->capture_default_str();
    app.add_option("--stride", stride, "Every stride-th pixel in x and y")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--radius", radius, "The AO radius in metres")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    if (const auto status = deepgi_tools::parse(app, argc, argv)) return *status;
    const auto depth0 = deepgi::read_pfm(dump / "gbuffer-depth-layer0.pfm");
    const auto depth1 = deepgi::read_pfm(dump / "gbuffer-depth-layer1.pfm");
    const auto normal0 = deepgi::read_pfm(dump / "gbuffer-normal-layer0.pfm");
    const auto normal1 = deepgi::read_pfm(dump / "gbuffer-normal-layer1.pfm");
    const auto truth = deepgi::read_pfm(reference / "reference-ao-visibility.pfm");
    const auto traced = deepgi::read_pfm(reference / "reference-depth-layer0.pfm");
    const int w = depth0.width, h = depth0.height;
    const deepgi::Scene scene = deepgi::load_scene(scene_name);
    // The dump of measure_ao.sh: a 16:9 viewport with the default guard band.
    const deepgi::RenderSettings settings =
        deepgi_tools::dump_viewport(w, h, deepgi::RenderSettings{}.guard_band_fraction);
    const auto layout = deepgi::frame_layout(settings);
    const glm::mat4 projection = deepgi::guard_band_projection(scene.default_camera, settings);
    const glm::vec2 ray_scale{1.0f / projection[0][0], 1.0f / projection[1][1]};
    auto position = [&](float x, float y, float z) {
        const glm::vec2 ndc = glm::vec2(x / float(w), y / float(h)) * 2.0f - 1.0f;
        return glm::vec3(ndc * ray_scale * z, -z);
    };
    const float s = 2.0f * ray_scale.y / float(h);  // pixel size per metre of depth
    const float r2 = radius * radius;
    double sum_abs = 0.0, sum = 0.0;
    long long count = 0;
    for (int y = layout.guard; y < h - layout.guard; y += stride) {
        for (int x = layout.guard; x < w - layout.guard; x += stride) {
            const float z = depth0.at(x, y);
            if (!deepgi::same_surface_depth(z, traced.at(x, y))) continue;
            const glm::vec3 p = position(x + 0.5f, y + 0.5f, z);
            const glm::vec3 n(normal0.at(x, y, 0), normal0.at(x, y, 1), normal0.at(x, y, 2));
            const float beta = bias + footprint_factor * s * z;
            const int rp = int(std::ceil(reach * radius / (s * z)));
            double occlusion = 0.0;
            for (int ty = std::max(0, y - rp); ty <= std::min(h - 1, y + rp); ++ty) {
                for (int tx = std::max(0, x - rp); tx <= std::min(w - 1, x + rp); ++tx) {
                    if (tx == x && ty == y) continue;
                    double best = 0.0;
                    for (int layer = 0; layer < layers; ++layer) {
                        const auto& d = layer == 0 ? depth0 : depth1;
                        const auto& nn = layer == 0 ? normal0 : normal1;
                        const float zy = d.at(tx, ty);
                        if (!(zy > 0.0f)) continue;
                        const glm::vec3 ny(nn.at(tx, ty, 0), nn.at(tx, ty, 1), nn.at(tx, ty, 2));
                        const glm::vec3 centre = position(tx + 0.5f, ty + 0.5f, zy);
                        double term = 0.0;
                        for (int sy = 0; sy < sub; ++sy) {
                            for (int sx = 0; sx < sub; ++sx) {
                                // Sub-pixel point on the tangent plane at the pixel centre.
                                const glm::vec3 ray =
                                    position(tx + (sx + 0.5f) / sub, ty + (sy + 0.5f) / sub, 1.0f);
                                const float t = glm::dot(ny, centre) / glm::dot(ny, ray);
                                const glm::vec3 q = sub == 1 ? centre : ray * t;
                                const glm::vec3 v = q - p;
                                const float vv = glm::dot(v, v);
                                if (vv >= r2 || vv <= 0.0f) continue;
                                const float lv = std::sqrt(vv);
                                const float vn = glm::dot(v, n);
                                float cx =
                                    subtract ? (vn - beta) / lv : (vn > beta ? vn / lv : 0.0f);
                                const float cy = std::abs(glm::dot(v, ny)) / lv;
                                if (cx <= 0.0f || cy <= 0.0f) continue;
                                const glm::vec3 dir = glm::normalize(q);
                                const float cv = std::max(std::abs(glm::dot(ny, dir)), clamp_view);
                                const float zq = -q.z;
                                float area = s * s * zq * zq / cv / float(sub * sub);
                                if (cos_phi) area *= -dir.z;
                                term += area * (1.0f - vv / r2) * cx * cy / vv;
                            }
                        }
                        best = std::max(best, term);
                    }
                    occlusion += best;
                }
            }
            // Signed, as sao.frag leaves the solid-angle visibility.
            const double av = 1.0 - occlusion / M_PI;
            const double error = av - truth.at(x, y);
            sum_abs += std::abs(error);
            sum += error;
            ++count;
        }
    }
    fmt::print("dense: {} pixels, MAE {:.4f}, bias {:+.4f}\n", count, sum_abs / count, sum / count);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return deepgi_tools::run_tool("deepgi_ao_dense_study", argc, argv, run);
}
