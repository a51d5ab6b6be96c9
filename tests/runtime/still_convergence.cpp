#include "still_convergence.hpp"

#include "deepgi/shader_loader.hpp"
#include "support/runtime_support.hpp"

#include <spiral/codegen.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace deepgi::convergence {

FloatImage viewport_of(const FloatImage& image, int width, int height) {
    if (image.width == width && image.height == height) return image;
    const int gx = (image.width - width) / 2;
    const int gy = (image.height - height) / 2;
    FloatImage out{width, height, image.channels,
                   std::vector<float>(std::size_t(width) * height * image.channels)};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < image.channels; ++c)
                out.pixels[(std::size_t(y) * width + x) * image.channels + c] =
                    image.at(x + gx, y + gy, c);
    return out;
}

namespace {

struct Guides {
    FloatImage depth, normal, albedo;  // viewport size
};

struct Images {
    FloatImage e, ao;  // blurred, viewport size
};

Images read_images(const Renderer& renderer, int width, int height) {
    return {viewport_of(renderer.read_pass_output("radiosity-blurred"), width, height),
            viewport_of(renderer.read_pass_output("ao-blurred"), width, height)};
}

// Pixels whose 9x9 window lies on one plane of one albedo: same normal
// (cos >= 0.999), same albedo (1e-3), depth within 5% of the centre's.
std::vector<std::size_t> flat_pixels(const Guides& guides) {
    const int w = guides.depth.width, h = guides.depth.height, r = 4;
    std::vector<std::size_t> out;
    for (int y = r; y < h - r; ++y) {
        for (int x = r; x < w - r; ++x) {
            const float d = guides.depth.at(x, y, 0);
            if (d <= 0.0f) continue;
            bool flat = true;
            for (int v = -r; v <= r && flat; ++v) {
                for (int u = -r; u <= r && flat; ++u) {
                    const float dd = guides.depth.at(x + u, y + v, 0);
                    float cos = 0.0f, albedo = 0.0f;
                    for (int c = 0; c < 3; ++c) {
                        cos += guides.normal.at(x, y, c) * guides.normal.at(x + u, y + v, c);
                        albedo = std::max(albedo, std::abs(guides.albedo.at(x, y, c) -
                                                           guides.albedo.at(x + u, y + v, c)));
                    }
                    flat = dd > 0.0f && std::abs(dd - d) <= 0.05f * d && cos >= 0.999f &&
                           albedo <= 1e-3f;
                }
            }
            if (flat) out.push_back(std::size_t(y) * w + x);
        }
    }
    return out;
}

// Relative RMS of the image minus its 9x9 box mean over `pixels`, against
// the image's RMS there (AO: against the mean occlusion).
double fine_grain(const FloatImage& image, const std::vector<std::size_t>& pixels, bool ao) {
    const int w = image.width, ch = ao ? 1 : 3;
    double squared = 0.0, norm = 0.0;
    for (std::size_t p : pixels) {
        const int x = int(p % w), y = int(p / w);
        for (int c = 0; c < ch; ++c) {
            double box = 0.0;
            for (int v = -4; v <= 4; ++v)
                for (int u = -4; u <= 4; ++u) box += image.at(x + u, y + v, c);
            box /= 81.0;
            const double value = image.at(x, y, c);
            squared += (value - box) * (value - box);
            norm += ao ? (1.0 - box) : value * value;
        }
    }
    if (pixels.empty()) return 0.0;
    return ao ? std::sqrt(squared / double(pixels.size())) / (norm / double(pixels.size()))
              : std::sqrt(squared / std::max(norm, 1e-30));
}

// Fills the error figures of `row` (not the fine grain).
void errors(const Images& image, const Images& converged, const FloatImage& depth,
            StillFigures& row) {
    double e2 = 0.0, c2 = 0.0, e1 = 0.0, c1 = 0.0, a2 = 0.0, occlusion = 0.0;
    std::size_t surface = 0;
    for (std::size_t p = 0; p < depth.pixels.size(); ++p) {
        if (depth.pixels[p] <= 0.0f) continue;
        ++surface;
        for (int c = 0; c < 3; ++c) {
            const double e = image.e.pixels[3 * p + c], t = converged.e.pixels[3 * p + c];
            e2 += (e - t) * (e - t);
            c2 += t * t;
            e1 += std::abs(e - t);
            c1 += std::abs(t);
        }
        const double a = image.ao.pixels[p], t = converged.ao.pixels[p];
        a2 += (a - t) * (a - t);
        occlusion += 1.0 - t;
    }
    const double n = double(std::max<std::size_t>(surface, 1));
    row.e_rms = std::sqrt(e2 / std::max(c2, 1e-30));
    row.e_mae = e1 / std::max(c1, 1e-30);
    row.ao_rms = std::sqrt(a2 / n) / std::max(occlusion / n, 1e-30);
}

}  // namespace

StillConvergence measure_still_convergence(const Scene& scene, const RenderSettings& settings,
                                           const std::vector<int>& frame_counts, int converged_taps,
                                           int converged_frames, const StillObserver& observer,
                                           const std::filesystem::path& shaders) {
    const int w = settings.width, h = settings.height;
    StillConvergence result;
    result.pixels = std::size_t(w) * h;

    // The converged image: the same pipeline with a denser radiosity header.
    Images converged;
    Guides guides;
    {
        test::TemporaryFolder folder;
        folder.write("radiosity_taps.glsl",
                     spiral::codegen::make_gather_header(
                         "radiosity", converged_taps, std::nullopt,
                         {fmt::format("converged image of the still-camera convergence "
                                      "measurement, {} taps",
                                      converged_taps)}));
        // The tap header's folder first: it holds that one file, which must
        // win over the build's (and over a copy in `shaders`).
        std::vector<std::filesystem::path> dirs =
            ShaderLoader::from_build_configuration(shaders).include_dirs();
        dirs.insert(dirs.begin(), folder.path());
        Renderer dense(scene, settings, ShaderLoader(dirs));
        for (int i = 0; i < converged_frames; ++i) dense.render(scene.default_camera);
        converged = read_images(dense, w, h);
        if (observer.converged_renderer) observer.converged_renderer(dense);
        guides = {viewport_of(dense.read_pass_output("gbuffer-depth-layer0"), w, h),
                  viewport_of(dense.read_pass_output("gbuffer-normal-layer0"), w, h),
                  viewport_of(dense.read_pass_output("gbuffer-albedo-layer0"), w, h)};
    }
    if (observer.converged) observer.converged(converged.ao, guides.depth);
    const std::vector<std::size_t> flat = flat_pixels(guides);
    result.flat_pixels = flat.size();
    result.converged_e_grain = fine_grain(converged.e, flat, false);
    result.converged_ao_grain = fine_grain(converged.ao, flat, true);

    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration(shaders));
    int rendered = 0;
    for (int n : frame_counts) {
        while (rendered < n) {
            renderer.render(scene.default_camera);
            ++rendered;
            if (observer.frame) observer.frame(renderer);
        }
        const Images image = read_images(renderer, w, h);
        if (observer.count) observer.count(renderer, n, image.ao);
        StillFigures row;
        row.frames = n;
        errors(image, converged, guides.depth, row);
        row.e_grain = fine_grain(image.e, flat, false);
        row.ao_grain = fine_grain(image.ao, flat, true);
        result.rows.push_back(row);
    }
    return result;
}

}  // namespace deepgi::convergence
