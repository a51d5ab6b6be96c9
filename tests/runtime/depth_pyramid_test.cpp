// The camera-space depth pyramid against the G-buffer it is built from and the
// rotated-grid rule.
#include "sao_reference.hpp"
#include "sao_test_support.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <bit>

namespace deepgi::test {
namespace {

std::vector<FloatImage> read_pyramid(const Renderer& renderer) {
    std::vector<FloatImage> levels;
    const auto names = renderer.pass_output_names();
    for (int level = 0;; ++level) {
        const std::string name = fmt::format("depth_pyramid-level{}", level);
        if (std::find(names.begin(), names.end(), name) == names.end()) return levels;
        levels.push_back(renderer.read_pass_output(name));
    }
}

TEST_CASE("depth pyramid: depth pyramid level 0 is the linear depth of both layers", "[pyramid]") {
    HeadlessContext context;
    const Scene scene = occluded_floor();
    Renderer renderer(scene, small_settings(160, 90), ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    const FloatImage base = read_pyramid(renderer).at(0);
    int layer1_surfaces = 0;
    for (int layer = 0; layer < 2; ++layer) {
        // The renderer's read-back converts stored near/z to metres on the CPU.
        const FloatImage depth =
            renderer.read_pass_output(fmt::format("gbuffer-depth-layer{}", layer));
        REQUIRE(depth.width == base.width);
        REQUIRE(depth.height == base.height);
        int mismatches = 0;
        for (int y = 0; y < base.height; ++y) {
            for (int x = 0; x < base.width; ++x) {
                const float expected = depth.at(x, y);
                const float actual = base.at(x, y, layer);
                if (expected == 0.0f ? actual != 0.0f
                                     : std::abs(actual - expected) > 1e-6f * expected)
                    ++mismatches;
                if (layer == 1 && expected > 0.0f) ++layer1_surfaces;
            }
        }
        INFO("layer " << layer);
        CHECK(mismatches == 0);
    }
    CHECK(layer1_surfaces > 100);  // the scene puts something behind layer 0
}

TEST_CASE("depth pyramid: depth pyramid levels are rotated-grid subsamples at any size",
          "[pyramid]") {
    HeadlessContext context;
    const Scene scene = occluded_floor(true);
    struct Size {
        int width;
        int height;
        float guard;
    };
    for (Size size : {Size{160, 90, 0.1f}, Size{161, 91, 0.1f}, Size{7, 3, 0.0f}, Size{2, 1, 0.0f},
                      Size{1, 1, 0.0f}, Size{1, 1, 0.5f}}) {
        for (int max_level : {5, 2, 0}) {
            RenderSettings settings = small_settings(size.width, size.height);
            settings.guard_band_fraction = size.guard;
            settings.depth_pyramid.max_mip_level = max_level;
            Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
            renderer.render(scene.default_camera);
            const std::vector<FloatImage> levels = read_pyramid(renderer);
            const FrameLayout layout = frame_layout(settings);
            const int largest = std::max(layout.internal_width, layout.internal_height);
            const int expected_levels =
                std::min(max_level, int(std::bit_width(unsigned(largest))) - 1) + 1;
            INFO(size.width << "x" << size.height << " (internal " << layout.internal_width << "x"
                            << layout.internal_height << "), max level " << max_level);
            REQUIRE(int(levels.size()) == expected_levels);
            for (std::size_t m = 1; m < levels.size(); ++m) {
                const FloatImage expected = reference_pyramid_level(levels[m - 1]);
                REQUIRE(levels[m].width == expected.width);
                REQUIRE(levels[m].height == expected.height);
                // Copies, never averages: every value is bit-identical to the chosen texel.
                CHECK(levels[m].pixels == expected.pixels);
            }
        }
    }
}

// Oracle: the back-face pass's own dump (reversed Z turned into metres on the
// CPU) at level 0 and the rotated-grid rule (reference_pyramid_level) above
// it, bit for bit: the thick spiral reads its solids' back faces from the
// pyramid's B and A in place of the back-face texture at the texel's source
// pixel, so the values must be the same floats; so does the march at level 0.
TEST_CASE("depth pyramid: with the thick spiral and the march B and A carry each layer's back face",
          "[pyramid]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    RenderSettings settings = small_settings(161, 91);  // odd sizes clamp the grid's last row
    settings.ao.method = AoMethod::solid_angle;
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    auto has_back_faces = [&] {
        const auto names = renderer.pass_output_names();
        return std::find(names.begin(), names.end(), "depth_pyramid-backface-level0") !=
               names.end();
    };
    CHECK_FALSE(has_back_faces());  // RG32F for the estimators without solids
    // Moving to the thick spiral reallocates the pyramid as RGBA32F.
    settings.ao.method = AoMethod::spiral_thick;
    renderer.set_settings(settings);
    renderer.render(scene.default_camera);
    REQUIRE(has_back_faces());
    std::vector<FloatImage> back_faces;
    for (int level = 0; level < int(read_pyramid(renderer).size()); ++level)
        back_faces.push_back(
            renderer.read_pass_output(fmt::format("depth_pyramid-backface-level{}", level)));
    REQUIRE(back_faces.size() > 3);
    int with_back_face = 0;
    for (int layer = 0; layer < 2; ++layer) {
        const FloatImage expected =
            renderer.read_pass_output(fmt::format("backface-depth-layer{}", layer));
        REQUIRE(expected.width == back_faces[0].width);
        REQUIRE(expected.height == back_faces[0].height);
        int mismatches = 0;
        for (int y = 0; y < expected.height; ++y) {
            for (int x = 0; x < expected.width; ++x) {
                mismatches += back_faces[0].at(x, y, layer) != expected.at(x, y);
                with_back_face += expected.at(x, y) > 0.0f;
            }
        }
        INFO("layer " << layer);
        CHECK(mismatches == 0);
    }
    // The boxes have back faces (the walls are open), or the comparison
    // would check zeros only.
    CHECK(with_back_face > 161 * 91 / 20);
    for (std::size_t m = 1; m < back_faces.size(); ++m) {
        INFO("level " << m);
        CHECK(back_faces[m].pixels == reference_pyramid_level(back_faces[m - 1]).pixels);
    }
    // The march, the default, reads the same level 0: the pyramid stays
    // RGBA32F with the same back faces.
    settings.ao.method = AoMethod::march;
    renderer.set_settings(settings);
    renderer.render(scene.default_camera);
    REQUIRE(has_back_faces());
    CHECK(renderer.read_pass_output("depth_pyramid-backface-level0").pixels ==
          back_faces[0].pixels);
}

}  // namespace
}  // namespace deepgi::test
