// The slice estimators of deep SAO, gtao and bitmask (docs/deep-sao.md,
// "Slice estimators"): per pixel against their CPU evaluation, an open plane,
// and the inside corner of two perpendicular planes against its closed form.
#include "ao_slice_reference.hpp"
#include "sao_test_support.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>

namespace deepgi::test {
namespace {

struct SliceFrame {
    SaoInputs inputs;
    FloatImage raw;
};

SliceFrame render_slice_frame(const Scene& scene, const RenderSettings& settings) {
    HeadlessContext context;
    Renderer renderer(scene, settings, ShaderLoader::from_build_configuration());
    renderer.render(scene.default_camera);
    SliceFrame frame;
    frame.inputs.pyramid.push_back(renderer.read_pass_output("depth_pyramid-level0"));
    frame.inputs.normals = renderer.read_pass_output("gbuffer-normal-layer0");
    frame.inputs.ray_scale = renderer_ray_scale(scene.default_camera, settings);
    frame.inputs.near_plane = scene.default_camera.near_plane;
    frame.raw = renderer.read_pass_output("ao-raw");
    return frame;
}

RenderSettings slice_settings(AoMethod method, int width, int height) {
    RenderSettings settings = small_settings(width, height);
    settings.ao.method = method;
    settings.ao.bias = default_ao_bias(method);
    return settings;
}

// A floor facing the camera at z = -2 and a wall x = `wall` facing -x from
// the floor up to z = -0.2, both unbounded in y: the floor's pixels left of
// the wall see an inside corner whose wall reaches past any radius below 1.8.
Scene inside_corner(float wall) {
    Scene scene;
    scene.name = "test-corner";
    SceneBuilder builder;
    const int white = builder.add_material({0.8f, 0.8f, 0.8f});
    builder.add_quad({-50, -50, -2}, {wall, -50, -2}, {wall, 50, -2}, {-50, 50, -2}, {0, 0, 1},
                     white);
    builder.add_quad({wall, -50, -2}, {wall, -50, -0.2f}, {wall, 50, -0.2f}, {wall, 50, -2},
                     {-1, 0, 0}, white);
    builder.finish(scene);
    scene.default_camera = camera_at_origin();
    scene.camera_path.keys = {scene.default_camera};
    return scene;
}

}  // namespace

TEST_CASE("ao slices: gtao and bitmask match their CPU evaluation per pixel", "[slices]") {
    for (AoMethod method : {AoMethod::gtao, AoMethod::bitmask}) {
        for (auto [layers, slices, steps, thickness] :
             {std::tuple{2, 2, 8, 0.2f}, std::tuple{1, 2, 8, 0.2f}, std::tuple{2, 4, 3, 0.5f}}) {
            for (const Scene& scene : {make_builtin_scene("cornell"), occluded_floor()}) {
                RenderSettings settings = slice_settings(method, 160, 90);
                settings.ao.layers = layers;
                settings.ao.slices = slices;
                settings.ao.steps = steps;
                settings.ao.thickness = thickness;
                const SliceFrame frame = render_slice_frame(scene, settings);
                const FloatImage expected = reference_slice_visibility(frame.inputs, settings.ao);
                std::size_t within = 0;
                int occluded = 0;
                float worst = 0.0f;
                for (std::size_t i = 0; i < expected.pixels.size(); ++i) {
                    const float error = std::abs(frame.raw.pixels[i] - expected.pixels[i]);
                    within += error <= 2e-3f;
                    worst = std::max(worst, error);
                    occluded += expected.pixels[i] < 0.9f;
                }
                const double fraction = double(within) / double(expected.pixels.size());
                INFO(to_string(method)
                     << " on " << scene.name << ", layers " << layers << ", " << slices << "x"
                     << steps << ": " << fraction * 100.0 << "% within 2e-3, worst " << worst
                     << ", " << occluded << " pixels below 0.9");
                CHECK(occluded > int(expected.pixels.size() / 50));
                // A sample on a sector's centre, or two samples at one horizon
                // angle, can fall either way in the last bit of atan.
                CHECK(fraction >= 0.995);
                CHECK(worst <= 0.1f);
            }
        }
    }
}

TEST_CASE("ao slices: an open plane has visibility 1", "[slices]") {
    for (AoMethod method : {AoMethod::gtao, AoMethod::bitmask}) {
        for (float distance : {0.5f, 3.0f, 40.0f}) {
            RenderSettings settings = slice_settings(method, 160, 90);
            settings.ao.radius = 2.0f;
            const SliceFrame frame = render_slice_frame(camera_facing_plane(distance), settings);
            const int guard = frame_layout(settings).guard;
            float lowest = 1.0f;
            for (int y = guard; y < frame.raw.height - guard; ++y)
                for (int x = guard; x < frame.raw.width - guard; ++x)
                    lowest = std::min(lowest, frame.raw.at(x, y));
            INFO(to_string(method) << ", plane at " << distance << " m: lowest " << lowest);
            CHECK(lowest >= 0.99f);
        }
    }
}

// The floor at distance d from the wall, radius r: V(d / r) of
// corner_visibility(), with the reference's falloff. Both estimators tend to
// it with many slices and steps (in every slice the wall's points within r
// hide the directions below the highest of them, and each rise of the
// horizon is first hit near the sample that raised it), the bitmask where
// its thickness reaches past the radius. What is left: the slices' angles
// sample the integral over the slice angle (two per pixel, so each pixel is
// noisy; the mean over a column of 40 pixels at one d is not), the highest
// sample lies up to one step below the wall's top within r, a rise counts
// with the falloff of the sample at its top, up to one step farther than
// where its lowest directions meet the wall, and the bitmask rounds each
// horizon to a sector centre. Bound: 0.04 on a column's mean (measured
// worst below, in the INFO line).
TEST_CASE("ao slices: the inside corner of two planes matches its closed form", "[slices]") {
    const float wall = 0.4f;
    for (AoMethod method : {AoMethod::gtao, AoMethod::bitmask}) {
        RenderSettings settings = slice_settings(method, 320, 180);
        settings.ao.radius = 1.0f;
        settings.ao.slices = 4;
        settings.ao.steps = 32;
        settings.ao.thickness = 100.0f;  // past the radius: the wall is a solid half-space
        const SliceFrame frame = render_slice_frame(inside_corner(wall), settings);
        const int height = frame.raw.height;
        double worst = 0.0;
        int columns = 0;
        for (int x = 0; x < frame.raw.width; ++x) {
            double sum = 0.0, distance = 0.0;
            int count = 0;
            for (int y = height / 2 - 20; y < height / 2 + 20; ++y) {
                const float depth = frame.inputs.pyramid[0].at(x, y, 0);
                if (std::abs(depth - 2.0f) > 1e-3f) continue;  // the floor only
                const float cx = float(x) + 0.5f;
                const float world_x =
                    (cx / float(frame.raw.width) * 2.0f - 1.0f) * frame.inputs.ray_scale.x * depth;
                distance += double(wall - world_x);
                sum += double(frame.raw.at(x, y));
                ++count;
            }
            if (count < 40) continue;  // a column on the wall
            distance /= count;
            if (distance > 1.2) continue;  // keep the samples' reach on the buffer
            const double expected = corner_visibility(distance, settings.ao.radius);
            worst = std::max(worst, std::abs(sum / count - expected));
            ++columns;
            CAPTURE(x, distance, sum / count, expected);
            CHECK(std::abs(sum / count - expected) <= 0.04);
        }
        INFO(to_string(method) << ": " << columns << " columns, worst column mean off by "
                               << worst);
        CHECK(columns > 50);
        WARN(to_string(method) << " corner: " << columns << " columns, worst " << worst);
    }
}

}  // namespace deepgi::test
