// The anti-aliasing filter on hand-made images: a constant image comes back
// byte for byte, and a hard tilted edge comes back closer to the edge's true
// pixel coverage (supersampled on the CPU), with its staircase steps smaller.
#include "deepgi/context.hpp"
#include "passes/passes.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace deepgi::test {
namespace {

struct Grey {
    int width = 0;
    int height = 0;
    std::vector<float> value;  // one per pixel, rows bottom to top
    float at(int x, int y) const {
        return value[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    }
};

// Runs the filter on an RGBA8 image and returns the RGBA8 result.
std::vector<std::uint8_t> run_filter(const std::vector<std::uint8_t>& rgba, int width, int height) {
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    Antialias antialias = create_antialias(loader);
    gl::Texture source = gl::create_texture_2d(GL_RGBA8, width, height);
    glTextureSubImage2D(source.get(), 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE,
                        rgba.data());
    gl::Texture target = gl::create_texture_2d(GL_RGBA8, width, height);
    gl::Framebuffer framebuffer = gl::create_framebuffer();
    glNamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT0, target.get(), 0);
    gl::VertexArray empty = gl::create_vertex_array();
    run_antialias(antialias, source.get(), framebuffer.get(), width, height, empty.get());
    std::vector<std::uint8_t> out(rgba.size());
    glGetTextureImage(target.get(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(out.size()), out.data());
    return out;
}

std::vector<std::uint8_t> to_rgba(const Grey& image) {
    std::vector<std::uint8_t> rgba;
    for (float v : image.value) {
        const auto byte = std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
        rgba.insert(rgba.end(), {byte, byte, byte, 255});
    }
    return rgba;
}

Grey from_rgba(const std::vector<std::uint8_t>& rgba, int width, int height) {
    Grey image{width, height, {}};
    for (std::size_t i = 0; i < rgba.size(); i += 4) image.value.push_back(rgba[i] / 255.0f);
    return image;
}

// dark below the line, light above it; `samples` per side per pixel (1: the
// pixel centre only, the aliased image a rasteriser makes).
Grey edge_image(int width, int height, const std::function<bool(float, float)>& light,
                int samples) {
    const float dark = 0.2f, bright = 0.8f;
    Grey image{width, height, {}};
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            int inside = 0;
            for (int j = 0; j < samples; ++j)
                for (int i = 0; i < samples; ++i)
                    inside += light(float(x) + (float(i) + 0.5f) / float(samples),
                                    float(y) + (float(j) + 0.5f) / float(samples));
            const float coverage = float(inside) / float(samples * samples);
            image.value.push_back(dark + (bright - dark) * coverage);
        }
    }
    return image;
}

struct EdgeMeasure {
    double mean_error = 0.0;    // against the coverage, over the pixels the edge crosses
    float largest_step = 0.0f;  // largest jump between neighbours along the edge
};

// along: (1, 0) for a mostly horizontal edge, (0, 1) for a mostly vertical one.
EdgeMeasure measure(const Grey& image, const Grey& truth, int along_x, int along_y) {
    EdgeMeasure m;
    int count = 0;
    for (int y = 2; y < image.height - 2; ++y) {
        for (int x = 2; x < image.width - 2; ++x) {
            const float t = truth.at(x, y);
            const bool crossed = t > 0.2001f && t < 0.7999f;
            const bool beside = truth.at(x + along_y, y + along_x) != truth.at(x, y) ||
                                truth.at(x - along_y, y - along_x) != truth.at(x, y);
            if (!crossed && !beside) continue;
            m.mean_error += std::abs(image.at(x, y) - t);
            ++count;
            m.largest_step = std::max(
                m.largest_step, std::abs(image.at(x + along_x, y + along_y) - image.at(x, y)));
        }
    }
    m.mean_error /= std::max(count, 1);
    return m;
}

}  // namespace

TEST_CASE("antialias: a constant image comes back unchanged", "[antialias]") {
    HeadlessContext context;
    for (auto [w, h] : {std::pair{48, 32}, std::pair{3, 2}, std::pair{1, 1}}) {
        std::vector<std::uint8_t> rgba;
        for (int i = 0; i < w * h; ++i) rgba.insert(rgba.end(), {77, 128, 201, 255});
        INFO(w << "x" << h);
        CHECK(run_filter(rgba, w, h) == rgba);
    }
}

TEST_CASE("antialias: a tilted edge comes closer to its coverage, with smaller steps",
          "[antialias]") {
    HeadlessContext context;
    const int w = 96, h = 96;
    struct Case {
        const char* name;
        std::function<bool(float, float)> light;
        int along_x, along_y;
        bool long_runs;  // the staircase's runs are 4 pixels or longer
    };
    const Case cases[] = {
        {"slope 0.23", [](float x, float y) { return y > 30.0f + 0.23f * x; }, 1, 0, true},
        {"slope 1 / 0.23", [](float x, float y) { return x > 30.0f + 0.23f * y; }, 0, 1, true},
        {"slope -0.6, runs of one or two pixels",
         [](float x, float y) { return y > 80.0f - 0.6f * x; }, 1, 0, false},
    };
    for (const Case& c : cases) {
        INFO(c.name);
        const Grey aliased = edge_image(w, h, c.light, 1);
        const Grey truth = edge_image(w, h, c.light, 16);
        const Grey filtered = from_rgba(run_filter(to_rgba(aliased), w, h), w, h);
        const EdgeMeasure before = measure(aliased, truth, c.along_x, c.along_y);
        const EdgeMeasure after = measure(filtered, truth, c.along_x, c.along_y);
        INFO("mean error against coverage " << before.mean_error << " -> " << after.mean_error
                                            << ", largest step " << before.largest_step << " -> "
                                            << after.largest_step);
        // The aliased staircase jumps the full contrast (0.6) along the edge.
        CHECK(before.largest_step == Approx(0.6f).margin(0.01f));
        // Targets: the error against the true coverage falls by at least a
        // third; along long runs no step is more than half the contrast.
        // Runs of one or two pixels leave the walk little to ramp over: there
        // the steps only have to shrink (measured 0.39 of 0.6, docs/deepgi.md).
        CHECK(after.mean_error <= before.mean_error * 2.0 / 3.0);
        if (c.long_runs)
            CHECK(after.largest_step <= 0.3f + 1.0f / 255.0f);
        else
            CHECK(after.largest_step < before.largest_step - 0.1f);
    }
}

}  // namespace deepgi::test
