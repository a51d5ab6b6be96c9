// Temporal filter of the ambient visibility against its invariants: averaging
// whole cycles of rotated tap patterns lowers the pixel-to-pixel noise and
// leaves the mean where a single frame puts it.
#include "sao_test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace deepgi::test {
namespace {

struct RegionStatistics {
    double mean = 0.0;
    double neighbour_difference = 0.0;  // mean |AV(x+1, y) - AV(x, y)|
    int pairs = 0;
};

// Over cornell's floor (upward normals; the default camera is unrotated, so
// camera space y is world y), away from the guard band.
RegionStatistics floor_statistics(const FloatImage& visibility, const FloatImage& normal,
                                  const FloatImage& depth) {
    RegionStatistics statistics;
    double sum = 0.0;
    int count = 0;
    auto on_floor = [&](int x, int y) {
        return depth.at(x, y, 0) > 0.0f && normal.at(x, y, 1) > 0.99f;
    };
    for (int y = 0; y < visibility.height; ++y) {
        for (int x = 0; x + 1 < visibility.width; ++x) {
            if (!on_floor(x, y)) continue;
            sum += visibility.at(x, y, 0);
            ++count;
            if (!on_floor(x + 1, y)) continue;
            statistics.neighbour_difference +=
                std::abs(visibility.at(x + 1, y, 0) - visibility.at(x, y, 0));
            ++statistics.pairs;
        }
    }
    REQUIRE(statistics.pairs > 500);
    statistics.mean = sum / count;
    statistics.neighbour_difference /= statistics.pairs;
    return statistics;
}

TEST_CASE("ao_temporal: 16 static frames halve the AO's pixel-to-pixel noise and keep its mean",
          "[ao_temporal]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Scene scene = make_builtin_scene("cornell");
    RenderSettings settings = small_settings(320, 180);
    Renderer renderer(scene, settings, loader);
    renderer.render(scene.default_camera);
    const FloatImage normal = renderer.read_pass_output("gbuffer-normal-layer0");
    const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
    const RegionStatistics one_frame =
        floor_statistics(renderer.read_pass_output("ao-raw"), normal, depth);
    // The filter's output on the first frame is that frame's SAO result.
    CHECK(renderer.read_pass_output("ao-temporal").pixels ==
          renderer.read_pass_output("ao-raw").pixels);
    for (int frame = 1; frame < 16; ++frame) renderer.render(scene.default_camera);
    const RegionStatistics filtered =
        floor_statistics(renderer.read_pass_output("ao-temporal"), normal, depth);
    WARN("AO over cornell's floor: neighbour difference one frame "
         << one_frame.neighbour_difference << ", after 16 frames " << filtered.neighbour_difference
         << "; mean " << one_frame.mean << " -> " << filtered.mean);
    CHECK(filtered.neighbour_difference <= 0.5 * one_frame.neighbour_difference);
    CHECK(std::abs(filtered.mean - one_frame.mean) <= 0.01);
}

TEST_CASE("ao_temporal: alpha 0 passes the raw SAO result through", "[ao_temporal]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Scene scene = make_builtin_scene("cornell");
    RenderSettings settings = small_settings(160, 90);
    settings.ao.alpha = 0.0f;
    Renderer renderer(scene, settings, loader);
    for (int frame = 0; frame < 3; ++frame) {
        renderer.render(scene.default_camera);
        CHECK(renderer.read_pass_output("ao-temporal").pixels ==
              renderer.read_pass_output("ao-raw").pixels);
    }
}

}  // namespace
}  // namespace deepgi::test
