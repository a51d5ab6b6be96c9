// The reference irradiance split by where the light comes from: the surface
// each sample's light leaves, held by layer 0, by layer 1 or by neither
// (layer_classifier()). The parts sum to E, leave E untouched, and fall
// where the geometry says in a case worked out by hand.
#include "deepgi/image_io.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"

#include "quad_scene.hpp"

#include <catch2/catch.hpp>

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

using deepgi::test::add_quad;

glm::dvec3 sum(const deepgi::IrradianceSample& s) {
    return s.by_layer[0] + s.by_layer[1] + s.by_layer[2];
}

}  // namespace

// An emitting wall (z = -2, facing +z, x in [-0.5, 0.5], height 0.6) over a
// floor, X on the floor c in front of it, no key light: all of E comes from
// the wall, pi L F with the form factor of the rectangle (as in
// reference_irradiance_test.cpp). The camera at (0, 1, 2) looks down -z.
//  - Nothing in between: the wall is the nearest front face along every
//    camera ray to it, so layer 0 holds all of E.
//  - A black board at z = -1 (3 m deep along the camera rays, the wall 4 m)
//    hides the wall and sends nothing. With a separation of 0.5 m layer 1 is
//    the wall (the camera rays to it stay above the floor until z = -2): all
//    of E is layer 1's. With 1.5 m layer 1 peels past the wall: all is
//    neither's.
// Bounds: the parts that must be 0 are exactly 0, except that a point on the
// wall's edge may miss it by float error along the camera ray and count as
// neither; the part that holds E holds at least 99.9% of it.
TEST_CASE("reference: a wall's light lands in the layer that holds the wall", "[reference]") {
    const float x1 = -0.5f, x2 = 0.5f, b = 0.6f, zw = -2.0f;
    const glm::vec3 emitted(1.0f, 0.5f, 0.25f);
    auto form_factor = [&](double x0, double c) {
        const double h = std::sqrt(double(b) * b + c * c);
        auto f = [&](double a) {
            return (std::atan(a / c) - c / h * std::atan(a / h)) / (2 * glm::pi<double>());
        };
        return f(x2 - x0) - f(x1 - x0);
    };
    deepgi::Camera camera;
    camera.position = {0.0f, 1.0f, 2.0f};
    deepgi::IrradianceRayBudget budget;
    budget.min_rays = budget.max_rays = 1 << 14;

    struct Case {
        const char* name;
        bool board;
        float separation;
        int holder;  // the part that must hold E
    };
    for (const Case& k : {Case{"in view", false, 0.5f, 0}, Case{"behind a board", true, 0.5f, 1},
                          Case{"behind a board, separation past it", true, 1.5f, 2}}) {
        deepgi::Scene scene;
        add_quad(scene, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}, {-50, 0, -50}, glm::vec3(0.5f),
                 glm::vec3(0.0f));
        add_quad(scene, {x1, 0, zw}, {x2, 0, zw}, {x2, b, zw}, {x1, b, zw}, glm::vec3(0.0f),
                 emitted);
        if (k.board)
            add_quad(scene, {-3, 0, -1}, {3, 0, -1}, {3, 3, -1}, {-3, 3, -1}, glm::vec3(0.0f),
                     glm::vec3(0.0f));
        scene.key_light.intensity = 0.0f;
        const deepgi::RayScene rays(scene);
        deepgi::RenderSettings render;
        render.width = 64;
        render.height = 36;
        render.min_separation = k.separation;
        const deepgi::LayerClassifier classify = deepgi::layer_classifier(rays, camera, render);
        for (double x0 : {0.0, 0.3}) {
            for (double c : {0.2, 0.6}) {
                const glm::vec3 x(float(x0), 0.0f, float(zw + c));
                const std::uint64_t seed = 31u + std::uint64_t(x0 * 100 + c * 10);
                const auto s =
                    deepgi::irradiance_at(rays, x, {0, 1, 0}, 50.0f, budget, seed, 1, classify);
                const auto plain = deepgi::irradiance_at(rays, x, {0, 1, 0}, 50.0f, budget, seed);
                INFO(k.name << ", x0 = " << x0 << ", c = " << c);
                // The classifier changes nothing of the estimate.
                REQUIRE(s.irradiance == plain.irradiance);
                REQUIRE(s.rays == plain.rays);
                const glm::dvec3 expected =
                    glm::pi<double>() * form_factor(x0, c) * glm::dvec3(emitted);
                for (int ch = 0; ch < 3; ++ch) {
                    INFO("channel " << ch << ": E " << s.irradiance[ch] << " (expected "
                                    << expected[ch] << "), parts " << s.by_layer[0][ch] << " "
                                    << s.by_layer[1][ch] << " " << s.by_layer[2][ch]);
                    // The case is what it says: E is the wall's form factor.
                    REQUIRE(s.irradiance[ch] ==
                            Approx(expected[ch])
                                .margin(5 * s.standard_error[ch] + 1e-3 * expected[ch]));
                    REQUIRE(sum(s)[ch] == Approx(s.irradiance[ch]).epsilon(1e-12));
                    REQUIRE(s.by_layer[k.holder][ch] >= 0.999 * s.irradiance[ch]);
                    // Layers that cannot hold the wall hold exactly nothing
                    // (neither may take an edge point's float error).
                    for (int part : {0, 1})
                        if (part != k.holder) REQUIRE(s.by_layer[part][ch] == 0.0);
                }
            }
        }
    }
}

// The images: E0 + E1 + E_neither = E per pixel (each rounded to float once),
// the split changes E not by a bit (the same as without a classifier, pixel by
// pixel), and `deepgi reference` writes the parts beside E.
TEST_CASE("reference: the irradiance split images sum to the irradiance", "[reference]") {
    namespace fs = std::filesystem;
    const fs::path directory = fs::temp_directory_path() / "deepgi_irradiance_split_test";
    fs::remove_all(directory);
    const std::string command = std::string(DEEPGI_EXECUTABLE) +
                                " reference --scene ref-bench --size 32x18 --no-ao "
                                "--irradiance-rays 512 --irradiance-min-rays 512 "
                                "--threads 2 --output " +
                                directory.string() + " > /dev/null";
    REQUIRE(std::system(command.c_str()) == 0);
    const auto whole = deepgi::read_pfm(directory / "reference-irradiance.pfm");
    const auto e0 = deepgi::read_pfm(directory / "reference-irradiance-layer0.pfm");
    const auto e1 = deepgi::read_pfm(directory / "reference-irradiance-layer1.pfm");
    const auto neither = deepgi::read_pfm(directory / "reference-irradiance-neither.pfm");
    for (const char* preview :
         {"reference-irradiance-layer0.png", "reference-irradiance-layer1.png",
          "reference-irradiance-neither.png"})
        CHECK(fs::exists(directory / preview));
    REQUIRE(whole.channels == 3);
    for (const auto* part : {&e0, &e1, &neither}) {
        REQUIRE(part->channels == 3);
        REQUIRE(part->pixels.size() == whole.pixels.size());
    }
    glm::dvec3 totals(0.0);
    double largest = 0.0;
    for (std::size_t i = 0; i < whole.pixels.size(); ++i) {
        const double parts =
            double(e0.pixels[i]) + double(e1.pixels[i]) + double(neither.pixels[i]);
        // Four float roundings of values at most E: a few ulps of E.
        REQUIRE(parts == Approx(double(whole.pixels[i])).margin(1e-6 * whole.pixels[i] + 1e-9));
        totals += glm::dvec3(e0.pixels[i], e1.pixels[i], neither.pixels[i]);
        largest = std::max(largest, double(whole.pixels[i]));
        REQUIRE(e0.pixels[i] >= 0.0f);
        REQUIRE(e1.pixels[i] >= 0.0f);
        REQUIRE(neither.pixels[i] >= 0.0f);
    }
    INFO("totals " << totals.x << " " << totals.y << " " << totals.z);
    REQUIRE(largest > 0.0);
    // The bench behind the posts: some light comes from surfaces only layer
    // 1 holds (as the occlusion split finds occluders only layer 1 sees).
    CHECK(totals.y > 0.0);
    CHECK(totals.x > totals.y);
    fs::remove_all(directory);
}
