// glTF scenes rendered end to end, their lights and shadows: alpha-masked
// shadow casters under a sun, KHR_lights_punctual directional, spot and
// point lights, and a point light's cube shadow map. Each expected radiance
// follows from the file's construction, the light's units and a pinhole
// projection worked out here (rendered_gltf.hpp).
#include "deepgi/context.hpp"
#include "rendered_gltf.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

using namespace deepgi;
using namespace deepgi::test;

namespace {

// Scene "sieve": a white floor (z = 0, 12 m square) under a directional sun
// travelling along (-1, 0, -1)/sqrt(2), so a caster at height 2 shadows the
// floor 2 m towards -X. Three masked casters at z = 2, 2 m square, centred on
// x = 4: at y = 0 a texture whose left half is a hole (alpha 0) and right
// half solid; at y = 3 factor alpha 0.8 x vertex alpha 0.5 = 0.4, under the
// cutoff 0.5 (all hole); at y = -3 factor alpha 1 x vertex alpha 0.6 (solid).
std::string sieve_file() {
    GltfBuilder b;
    const int white = b.material("{}");
    const int sampler = b.sampler(R"({"magFilter":9728,"minFilter":9728})");  // nearest
    const int half =
        b.texture(test::encode_png(2, 1, {255, 255, 255, 0, 255, 255, 255, 255}), sampler);
    const int textured = b.material(fmt::format(
        R"({{"alphaMode":"MASK","alphaCutoff":0.5,"pbrMetallicRoughness":{{"baseColorTexture":{{"index":{}}}}}}})",
        half));
    const int faint = b.material(
        R"({"alphaMode":"MASK","alphaCutoff":0.5,"pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.8]}})");
    const int plain = b.material(R"({"alphaMode":"MASK","alphaCutoff":0.5})");
    auto vertex_alpha = [&](float a) {
        std::vector<float> colours;
        for (int i = 0; i < 4; ++i) colours.insert(colours.end(), {1, 1, 1, a});
        return fmt::format(R"(,"COLOR_0":{})", b.accessor(colours, 5126, "VEC4", 4));
    };
    b.mesh_node(b.quad(0, 0, 0, 12.0f, white));
    b.mesh_node(b.quad(4, 0, 2, 2.0f, textured));
    b.mesh_node(b.quad(4, 3, 2, 2.0f, faint, 4, vertex_alpha(0.5f)));
    b.mesh_node(b.quad(4, -3, 2, 2.0f, plain, 4, vertex_alpha(0.6f)));
    b.light(R"({"type":"directional","intensity":2049})");  // 3 W/m^2
    const float s = std::sin(glm::radians(22.5f)), c = std::cos(glm::radians(22.5f));
    b.node(fmt::format(
        R"("rotation":[0,{},0,{}],"extensions":{{"KHR_lights_punctual":{{"light":0}}}})", s, c));
    b.use_extension("KHR_lights_punctual");
    return b.json();
}

}  // namespace

TEST_CASE("gltf render: alpha-masked casters let the light through their holes",
          "[runtime][gltf][render]") {
    HeadlessContext context;
    const Scene scene = load(sieve_file());
    Camera camera;
    camera.position = {0, 0, 10};
    camera.vertical_fov = 0.8f;
    const Frame frame = render(scene, camera);
    const Pinhole pinhole{camera.position, camera.vertical_fov};
    // A caster point (x, y, 2) shades the floor at (x - 2, y, 0); seen from
    // the camera, the floor points below are in front of every caster.
    auto floor_light = [&](float x, float y) {
        const glm::ivec2 p = pinhole.pixel({x, y, 0}, frame.layout);
        CHECK(frame.depth0.at(p.x, p.y) == Approx(10.0f).epsilon(2e-3));
        return frame.light0.at(p.x, p.y, 0);
    };
    // Sun at 45 degrees on a white floor: 3 W/m^2 x cos 45 / pi.
    const float open = 3.0f * std::cos(glm::radians(45.0f)) / glm::pi<float>();
    CHECK(floor_light(-3.0f, 0.0f) == Approx(open).epsilon(0.02));
    CHECK(floor_light(1.5f, 0.0f) == Approx(open).epsilon(0.02));  // under the texture's hole
    CHECK(floor_light(2.5f, 0.0f) < 0.02f * open);                 // under its solid half
    CHECK(floor_light(2.0f, 3.0f) == Approx(open).epsilon(0.02));  // 0.8 x 0.5 < cutoff
    CHECK(floor_light(2.0f, -3.0f) < 0.02f * open);                // 1 x 0.6 >= cutoff
}

namespace {

// Scene "lights": two quads 1.5 m above and below the origin, the upper one
// turned 45 degrees towards +X, the lower one towards -X, seen from
// (0, 0, 10). `light` is a KHR_lights_punctual light placed at `x` with its
// -Z turned to travel towards -X (x > 0) or +X (x < 0).
std::string lights_file(const std::string& light, float x) {
    GltfBuilder b;
    const int white = b.material("{}");
    const float s45 = std::sin(glm::radians(22.5f)), c45 = std::cos(glm::radians(22.5f));
    b.mesh_node(b.quad(0, 0, 0, 1.6f, white),
                fmt::format(R"(,"translation":[0,1.5,0],"rotation":[0,{},0,{}])", s45, c45));
    b.mesh_node(b.quad(0, 0, 0, 1.6f, white),
                fmt::format(R"(,"translation":[0,-1.5,0],"rotation":[0,{},0,{}])", -s45, c45));
    b.light(light);
    const float half_turn = x > 0 ? glm::radians(45.0f) : -glm::radians(45.0f);
    b.node(fmt::format(
        R"("translation":[{},1.5,0],"rotation":[0,{},0,{}],"extensions":{{"KHR_lights_punctual":{{"light":0}}}})",
        x, std::sin(half_turn), std::cos(half_turn)));
    b.use_extension("KHR_lights_punctual");
    return b.json();
}

}  // namespace

TEST_CASE("gltf render: directional, spot and point lights brighten the side facing them",
          "[runtime][gltf][render]") {
    HeadlessContext context;
    const std::string sun = R"({"type":"directional","intensity":2049})";  // 3 W/m^2
    const std::string spot =
        R"({"type":"spot","intensity":34150,"spot":{"innerConeAngle":0.4,"outerConeAngle":0.6}})";
    const std::string point = R"({"type":"point","intensity":34150})";
    for (const auto& [kind, light] :
         {std::pair{LightKind::directional, sun}, std::pair{LightKind::spot, spot},
          std::pair{LightKind::point, point}}) {
        INFO("light " << light);
        for (float x : {8.0f, -8.0f}) {
            INFO("light at x = " << x);
            const Scene scene = load(lights_file(light, x));
            REQUIRE(scene.key_light.kind == kind);
            Camera camera;
            camera.position = {0, 0, 10};
            camera.vertical_fov = 0.8f;
            const Frame frame = render(scene, camera);
            const Pinhole pinhole{camera.position, camera.vertical_fov};
            const glm::ivec2 upper = pinhole.pixel({0, 1.5f, 0}, frame.layout);
            const glm::ivec2 lower = pinhole.pixel({0, -1.5f, 0}, frame.layout);
            const float up = frame.light0.at(upper.x, upper.y, 0);
            const float down = frame.light0.at(lower.x, lower.y, 0);
            // From +X the upper quad faces the light, from -X the lower one.
            const float lit = x > 0 ? up : down;
            const float dark = x > 0 ? down : up;
            CHECK(lit > 0.1f);
            CHECK(dark < 0.1f * lit);
        }
    }
}

TEST_CASE("gltf render: a point key light drops nothing and warns of nothing",
          "[runtime][gltf][render]") {
    const Scene scene = load(lights_file(R"({"type":"point","name":"bulb","intensity":100})", 8));
    CHECK(scene.key_light.kind == LightKind::point);
    for (const auto& warning : scene.warnings) CHECK(warning.find("light") == std::string::npos);
    CHECK(scene.indices.size() == 12);
}

namespace {

// Scene "lamp": a point light 3 m above a white floor (z = 0, 14 m square)
// and five 0.6 m casters 1.5 m up, halfway between the light and the floor
// points they shade: (2, 0) under the light's -Z cube face, (5, 0), (-5, 0),
// (0, 5), (0, -5) under its +X, -X, +Y and -Y faces.
constexpr float kLampHeight = 3.0f;
const glm::vec2 kLampShadows[] = {{2, 0}, {5, 0}, {-5, 0}, {0, 5}, {0, -5}};

std::string lamp_file() {
    GltfBuilder b;
    const int white = b.material("{}");
    b.mesh_node(b.quad(0, 0, 0, 14.0f, white));
    for (glm::vec2 s : kLampShadows)
        b.mesh_node(b.quad(s.x / 2, s.y / 2, kLampHeight / 2, 0.6f, white));
    b.light(R"({"type":"point","intensity":6830})");  // 10 W/sr
    b.node(fmt::format(
        R"("translation":[0,0,{}],"extensions":{{"KHR_lights_punctual":{{"light":0}}}})",
        kLampHeight));
    b.use_extension("KHR_lights_punctual");
    return b.json();
}

}  // namespace

TEST_CASE("gltf render: a point light's cube shadow darkens the floor behind each caster",
          "[runtime][gltf][render]") {
    HeadlessContext context;
    const Scene scene = load(lamp_file());
    REQUIRE(scene.key_light.kind == LightKind::point);
    Camera camera;
    camera.position = {0, 0, 10};
    camera.vertical_fov = 1.3f;
    const Frame frame = render(scene, camera);
    const Pinhole pinhole{camera.position, camera.vertical_fov};
    const glm::vec3 light(0, 0, kLampHeight);
    // Lambertian white floor: 10 W/sr x cos / d^2 / pi.
    auto open = [&](glm::vec3 p) {
        const glm::vec3 offset = light - p;
        const float d2 = glm::dot(offset, offset);
        return 10.0f * (offset.z / std::sqrt(d2)) / d2 / glm::pi<float>();
    };
    // The floor point seen through the centre of the pixel that (x, y, 0)
    // falls in (pixels are 14 cm on the floor, enough to move the light 3 %).
    auto floor_point = [&](glm::ivec2 p) {
        const glm::vec2 ndc =
            (glm::vec2(p - frame.layout.guard) + 0.5f) / glm::vec2(kWidth, kHeight) * 2.0f - 1.0f;
        const float t = std::tan(camera.vertical_fov / 2);
        return camera.position + 10.0f * glm::vec3(ndc.x * t * kWidth / kHeight, ndc.y * t, -1.0f);
    };
    auto floor_light = [&](glm::vec2 xy) {
        const glm::ivec2 p = pinhole.pixel({xy.x, xy.y, 0}, frame.layout);
        CHECK(frame.depth0.at(p.x, p.y) == Approx(10.0f).epsilon(2e-3));
        return std::pair{frame.light0.at(p.x, p.y, 0), open(floor_point(p))};
    };
    for (glm::vec2 s : kLampShadows) {
        INFO("shadow at " << s.x << ", " << s.y);
        const auto [shadowed, unblocked] = floor_light(s);
        CHECK(shadowed < 0.02f * unblocked);
        // Beside it (1 m off the caster's 1.2 m shadow, across the direction
        // from the light) the floor is lit.
        const auto [lit, expected] = floor_light(s + glm::vec2(-s.y, s.x) / glm::length(s));
        CHECK(lit == Approx(expected).epsilon(0.02));
    }
}

TEST_CASE("gltf render: a point light is candela / 683 over distance squared, cut by its range",
          "[runtime][gltf][render]") {
    HeadlessContext context;
    Camera camera;
    camera.position = {0, 0, 10};
    camera.vertical_fov = 0.8f;
    const Pinhole pinhole{camera.position, camera.vertical_fov};
    // The light sits 8 m from the upper quad's centre along +X; the quad's
    // normal is 45 degrees from +X, its albedo white.
    auto upper_radiance = [&](const std::string& extra) {
        const Scene scene =
            load(lights_file(R"({"type":"point","intensity":34150)" + extra + "}", 8));
        const Frame frame = render(scene, camera);
        const glm::ivec2 upper = pinhole.pixel({0, 1.5f, 0}, frame.layout);
        // The pixel's surface point, from its depth along its view ray.
        const float depth = frame.depth0.at(upper.x, upper.y);
        const glm::vec2 ndc =
            (glm::vec2(upper - frame.layout.guard) + 0.5f) / glm::vec2(kWidth, kHeight) * 2.0f -
            1.0f;
        const float t = std::tan(camera.vertical_fov / 2);
        const glm::vec3 point =
            camera.position + depth * glm::vec3(ndc.x * t * kWidth / kHeight, ndc.y * t, -1.0f);
        return std::pair{frame.light0.at(upper.x, upper.y, 0), point};
    };
    const glm::vec3 light(8, 1.5f, 0);
    const glm::vec3 normal(std::sin(glm::radians(45.0f)), 0, std::cos(glm::radians(45.0f)));
    auto expected = [&](glm::vec3 point, float range) {
        const glm::vec3 offset = light - point;
        const float d2 = glm::dot(offset, offset);
        const float window =
            range > 0 ? std::clamp(1.0f - d2 * d2 / std::pow(range, 4.0f), 0.0f, 1.0f) : 1.0f;
        return 50.0f / d2 * window * glm::dot(normal, offset / std::sqrt(d2)) / glm::pi<float>();
    };
    const auto [unlimited, point] = upper_radiance("");
    CHECK(unlimited == Approx(expected(point, 0)).epsilon(0.02));
    const auto [windowed, point16] = upper_radiance(R"(,"range":16)");
    CHECK(windowed == Approx(expected(point16, 16)).epsilon(0.02));
    CHECK(windowed < 0.97f * unlimited);                   // 1 - (8/16)^4 = 0.9375
    CHECK(upper_radiance(R"(,"range":7)").first == 0.0f);  // out of range
}
