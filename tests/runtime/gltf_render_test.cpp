// glTF scenes rendered end to end, their geometry and materials: files built
// here (camera, strip, fan, lines, double-sided plane, alpha mask, vertex
// colours, textures) and real sample models from a Debian package. Each
// expected pixel follows from the file's construction and a pinhole
// projection worked out here (rendered_gltf.hpp). Lights and shadows are
// gltf_lights_test.cpp.
#include "deepgi/context.hpp"
#include "../support/skip.hpp"
#include "rendered_gltf.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <unistd.h>

namespace fs = std::filesystem;
using namespace deepgi;
using namespace deepgi::test;

namespace {

float srgb_to_linear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

glm::vec3 rgb(const FloatImage& image, glm::ivec2 p) {
    return {image.at(p.x, p.y, 0), image.at(p.x, p.y, 1), image.at(p.x, p.y, 2)};
}

bool near(glm::vec3 a, glm::vec3 b, float tolerance) {
    return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tolerance)));
}

// The camera for Scene "board": at (1, 0, 10) looking down -Z.
constexpr float kBoardFov = 0.7f;
const glm::vec3 kBoardEye(1.0f, 0.0f, 10.0f);

// Two rows of quads at z = 0, each 1.6 m: top row strip (red), fan (green),
// lines (nothing), emissive texture; bottom row COLOR_0 as float VEC3,
// normalised unsigned byte VEC4 and normalised unsigned short VEC4.
struct Board {
    std::string json;
    static constexpr float columns[4] = {-3.5f, -1.0f, 1.5f, 4.0f};
    static constexpr float top = 1.4f, bottom = -1.4f;
};

Board board_file() {
    GltfBuilder b;
    const int red = b.material(R"({"pbrMetallicRoughness":{"baseColorFactor":[1,0,0,1]}})");
    const int green = b.material(R"({"pbrMetallicRoughness":{"baseColorFactor":[0,1,0,1]}})");
    const int white = b.material(R"({})");
    // Emissive: a 1x1 texture (sRGB 128, 64, 255) x factor (1, 0.5, 0.25) x strength 2.
    const int emissive_texture = b.texture(test::encode_png(1, 1, {128, 64, 255, 255}));
    const int glowing = b.material(fmt::format(
        R"({{"emissiveFactor":[1,0.5,0.25],"emissiveTexture":{{"index":{}}},)"
        R"("extensions":{{"KHR_materials_emissive_strength":{{"emissiveStrength":2}}}}}})",
        emissive_texture));
    b.use_extension("KHR_materials_emissive_strength");
    const auto& c = Board::columns;
    b.mesh_node(b.quad(c[0], Board::top, 0, 1.6f, red, 5));
    b.mesh_node(b.quad(c[1], Board::top, 0, 1.6f, green, 6));
    // Two line primitives over the third slot: skipped, one warning.
    const int line_points = b.vec3s({{c[2] - 0.8f, Board::top, 0}, {c[2] + 0.8f, Board::top, 0}});
    b.mesh_node(fmt::format(R"({{"attributes":{{"POSITION":{0}}},"mode":1}},)"
                            R"({{"attributes":{{"POSITION":{0}}},"mode":3}})",
                            line_points));
    b.mesh_node(b.quad(c[3], Board::top, 0, 1.6f, glowing));
    const int float_colours = b.accessor(
        std::vector<float>{0.2f, 0.4f, 0.8f, 0.2f, 0.4f, 0.8f, 0.2f, 0.4f, 0.8f, 0.2f, 0.4f, 0.8f},
        5126, "VEC3", 4);
    b.mesh_node(b.quad(c[0], Board::bottom, 0, 1.6f, white, 4,
                       fmt::format(R"(,"COLOR_0":{})", float_colours)));
    const int byte_colours = b.accessor(std::vector<std::uint8_t>{255, 51, 0, 255, 255, 51, 0, 255,
                                                                  255, 51, 0, 255, 255, 51, 0, 255},
                                        5121, "VEC4", 4, true);
    b.mesh_node(b.quad(c[1], Board::bottom, 0, 1.6f, white, 4,
                       fmt::format(R"(,"COLOR_0":{})", byte_colours)));
    std::vector<std::uint16_t> shorts;
    for (int i = 0; i < 4; ++i) shorts.insert(shorts.end(), {0, 65535, 13107, 65535});
    const int short_colours = b.accessor(shorts, 5123, "VEC4", 4, true);
    b.mesh_node(b.quad(c[2], Board::bottom, 0, 1.6f, white, 4,
                       fmt::format(R"(,"COLOR_0":{})", short_colours)));
    const int camera = b.camera(fmt::format(
        R"({{"type":"perspective","perspective":{{"yfov":{},"znear":0.1,"aspectRatio":1.78}}}})",
        kBoardFov));
    b.node(fmt::format(R"("camera":{},"translation":[{},{},{}])", camera, kBoardEye.x, kBoardEye.y,
                       kBoardEye.z));
    return {b.json()};
}

}  // namespace

TEST_CASE("gltf render: the file's camera frames the board where a pinhole puts it",
          "[runtime][gltf][render]") {
    HeadlessContext context;
    const Scene scene = load(board_file().json);
    const Pinhole pinhole{kBoardEye, kBoardFov};
    const Frame frame = render(scene, scene.default_camera);
    // The strip's centre: red, 10 m away.
    const glm::ivec2 centre = pinhole.pixel({Board::columns[0], Board::top, 0}, frame.layout);
    CHECK(frame.depth0.at(centre.x, centre.y) == Approx(10.0f).epsilon(1e-3));
    CHECK(near(rgb(frame.albedo0, centre), {1, 0, 0}, 0.01f));
    // Just inside and just outside the strip's left edge (0.8 m from its
    // centre; a pixel is about 0.07 m here).
    const glm::ivec2 inside =
        pinhole.pixel({Board::columns[0] - 0.7f, Board::top, 0}, frame.layout);
    const glm::ivec2 outside =
        pinhole.pixel({Board::columns[0] - 0.9f, Board::top, 0}, frame.layout);
    CHECK(frame.depth0.at(inside.x, inside.y) > 0.0f);
    CHECK(frame.depth0.at(outside.x, outside.y) == 0.0f);
}

TEST_CASE("gltf render: strip and fan are present, lines absent, vertex colours multiply",
          "[runtime][gltf][render]") {
    HeadlessContext context;
    const Scene scene = load(board_file().json);
    const Pinhole pinhole{kBoardEye, kBoardFov};
    for (Generator generator : {Generator::peel, Generator::previous, Generator::reproject}) {
        INFO("generator " << int(generator));
        const Frame frame = render(scene, scene.default_camera, generator);
        auto at = [&](int column, float y, float dx = 0, float dy = 0) {
            return pinhole.pixel({Board::columns[column] + dx, y + dy, 0}, frame.layout);
        };
        // Every corner region of the strip and fan, so both triangles are there.
        for (float dx : {-0.5f, 0.5f}) {
            for (float dy : {-0.5f, 0.5f}) {
                CHECK(near(rgb(frame.albedo0, at(0, Board::top, dx, dy)), {1, 0, 0}, 0.01f));
                CHECK(near(rgb(frame.albedo0, at(1, Board::top, dx, dy)), {0, 1, 0}, 0.01f));
            }
        }
        // The lines' slot is empty along the line itself.
        for (float dx : {-0.6f, 0.0f, 0.6f}) {
            const glm::ivec2 p = at(2, Board::top, dx);
            CHECK(frame.depth0.at(p.x, p.y) == 0.0f);
        }
        // COLOR_0 x white base colour: float, unsigned byte, unsigned short.
        CHECK(near(rgb(frame.albedo0, at(0, Board::bottom)), {0.2f, 0.4f, 0.8f}, 0.01f));
        CHECK(near(rgb(frame.albedo0, at(1, Board::bottom)), {1.0f, 0.2f, 0.0f}, 0.01f));
        CHECK(near(rgb(frame.albedo0, at(2, Board::bottom)), {0.0f, 1.0f, 0.2f}, 0.01f));
    }
}

TEST_CASE("gltf render: emissive texture x factor x strength reaches the G-buffer",
          "[runtime][gltf][render]") {
    HeadlessContext context;
    const Scene scene = load(board_file().json);
    const Frame frame = render(scene, scene.default_camera);
    const glm::ivec2 p =
        Pinhole{kBoardEye, kBoardFov}.pixel({Board::columns[3], Board::top, 0}, frame.layout);
    const glm::vec3 expected =
        glm::vec3(srgb_to_linear(128 / 255.0f), srgb_to_linear(64 / 255.0f), srgb_to_linear(1.0f)) *
        glm::vec3(1.0f, 0.5f, 0.25f) * 2.0f;
    CHECK(near(rgb(frame.emissive0, p), expected, 0.01f));
    // Quads without an emissive texture or factor stay dark.
    const glm::ivec2 q =
        Pinhole{kBoardEye, kBoardFov}.pixel({Board::columns[0], Board::top, 0}, frame.layout);
    CHECK(rgb(frame.emissive0, q) == glm::vec3(0.0f));
}

TEST_CASE("gltf render: the lines' warning is printed once", "[runtime][gltf][render]") {
    const fs::path directory = fs::temp_directory_path() / fmt::format("gltf_render_{}", getpid());
    fs::create_directories(directory);
    const fs::path file = directory / "board.gltf";
    std::ofstream(file) << board_file().json;
    const fs::path errors = directory / "stderr.txt";
    const std::string command = fmt::format(
        "'{}' --headless --scene '{}' --size 64x36 --output '{}' 2> '{}'", DEEPGI_EXECUTABLE,
        file.string(), (directory / "out.png").string(), errors.string());
    REQUIRE(std::system(command.c_str()) == 0);
    std::stringstream text;
    text << std::ifstream(errors).rdbuf();
    const std::string all = text.str();
    const std::string warning = "skipped 2 point or line primitive(s): they are not surfaces";
    std::size_t count = 0;
    for (std::size_t at = all.find(warning); at != std::string::npos;
         at = all.find(warning, at + 1))
        ++count;
    CHECK(count == 1);
    fs::remove_all(directory);
}

namespace {

// Scene "cutout": left, a double-sided blue plane (x = -3, y = 1) above a
// single-sided grey one (x = -3, y = -1.2). Right (x in [1, 5]): an occluder
// at z = 3 over y in [0.3, 1.3]; a MASK quad at z = 0 whose left half
// (texture alpha 0) is cut; a wall at z = -3.
std::string cutout_file() {
    GltfBuilder b;
    const int blue =
        b.material(R"({"doubleSided":true,"pbrMetallicRoughness":{"baseColorFactor":[0,0,1,1]}})");
    const int grey = b.material(R"({"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.5,0.5,1]}})");
    const int sampler = b.sampler(R"({"magFilter":9728,"minFilter":9728})");  // nearest
    const int cut = b.texture(test::encode_png(2, 1, {255, 255, 0, 0, 0, 0, 255, 255}), sampler);
    const int masked = b.material(fmt::format(
        R"({{"alphaMode":"MASK","alphaCutoff":0.5,"pbrMetallicRoughness":{{"baseColorTexture":{{"index":{}}}}}}})",
        cut));
    const int orange = b.material(R"({"pbrMetallicRoughness":{"baseColorFactor":[1,0.5,0,1]}})");
    const int white = b.material(R"({})");
    b.mesh_node(b.quad(-3, 1, 0, 1.6f, blue));
    b.mesh_node(b.quad(-3, -1.2f, 0, 1.6f, grey));
    b.mesh_node(b.quad(3, 0.8f, 3, 1.0f, orange), R"(,"scale":[4,1,1],"translation":[-9,0,0])");
    b.mesh_node(b.quad(3, 0, 0, 4.0f, masked));
    b.mesh_node(b.quad(3, 0, -3, 5.0f, white));
    return b.json();
}

}  // namespace

TEST_CASE("gltf render: a double-sided plane shows both faces, a single-sided one only its front",
          "[runtime][gltf][render]") {
    HeadlessContext context;
    const Scene scene = load(cutout_file());
    const float fov = 0.8f;
    Camera front;
    front.position = {0, 0, 10};
    front.vertical_fov = fov;
    Camera back = front;
    back.position = {0, 0, -10};
    back.yaw = glm::pi<float>();  // looking down +Z
    const Frame seen_front = render(scene, front);
    const Frame seen_back = render(scene, back);
    const glm::ivec2 plane_front =
        Pinhole{front.position, fov}.pixel({-3, 1, 0}, seen_front.layout);
    const glm::ivec2 plane_back =
        Pinhole{back.position, fov, true}.pixel({-3, 1, 0}, seen_back.layout);
    const glm::ivec2 single_front =
        Pinhole{front.position, fov}.pixel({-3, -1.2f, 0}, seen_front.layout);
    const glm::ivec2 single_back =
        Pinhole{back.position, fov, true}.pixel({-3, -1.2f, 0}, seen_back.layout);
    CHECK(near(rgb(seen_front.albedo0, plane_front), {0, 0, 1}, 0.01f));
    CHECK(near(rgb(seen_back.albedo0, plane_back), {0, 0, 1}, 0.01f));
    // Camera-space normals face the camera (+Z) from either side.
    CHECK(seen_front.normal0.at(plane_front.x, plane_front.y, 2) > 0.99f);
    CHECK(seen_back.normal0.at(plane_back.x, plane_back.y, 2) > 0.99f);
    CHECK(seen_front.depth0.at(single_front.x, single_front.y) > 0.0f);
    CHECK(seen_back.depth0.at(single_back.x, single_back.y) == 0.0f);
}

TEST_CASE("gltf render: the alpha mask cuts holes in both G-buffer layers for every generator",
          "[runtime][gltf][render]") {
    HeadlessContext context;
    const Scene scene = load(cutout_file());
    Camera camera;
    camera.position = {0, 0, 10};
    camera.vertical_fov = 0.8f;
    const Pinhole pinhole{camera.position, camera.vertical_fov};
    for (Generator generator : {Generator::peel, Generator::previous, Generator::reproject}) {
        INFO("generator " << int(generator));
        const Frame frame = render(scene, camera, generator);
        // Below the occluder: layer 0 is the wall through the hole (13 m), the
        // masked quad where it is solid (10 m).
        const glm::ivec2 hole0 = pinhole.pixel({2, -1, 0}, frame.layout);
        const glm::ivec2 solid0 = pinhole.pixel({4, -1, 0}, frame.layout);
        CHECK(frame.depth0.at(hole0.x, hole0.y) == Approx(13.0f).epsilon(2e-3));
        CHECK(near(rgb(frame.albedo0, hole0), {1, 1, 1}, 0.01f));
        CHECK(frame.depth0.at(solid0.x, solid0.y) == Approx(10.0f).epsilon(2e-3));
        CHECK(near(rgb(frame.albedo0, solid0), {0, 0, 1}, 0.01f));
        // Behind the occluder (7 m): layer 1 is the wall through the hole,
        // the masked quad where it is solid (points on the masked quad).
        const glm::ivec2 hole1 = pinhole.pixel({2, 1, 0}, frame.layout);
        const glm::ivec2 solid1 = pinhole.pixel({4.5f, 1, 0}, frame.layout);
        CHECK(frame.depth0.at(hole1.x, hole1.y) == Approx(7.0f).epsilon(2e-3));
        CHECK(frame.depth1.at(hole1.x, hole1.y) == Approx(13.0f).epsilon(2e-3));
        CHECK(frame.depth0.at(solid1.x, solid1.y) == Approx(7.0f).epsilon(2e-3));
        CHECK(frame.depth1.at(solid1.x, solid1.y) == Approx(10.0f).epsilon(2e-3));
        CHECK(near(rgb(frame.albedo1, solid1), {0, 0, 1}, 0.01f));
    }
}

TEST_CASE("gltf render: base colour textures are read through their sampler's wrap and filter",
          "[runtime][gltf][render]") {
    HeadlessContext context;
    GltfBuilder b;
    // 2x1 texels, red then green; the texture twice across each quad.
    const auto red_green = test::encode_png(2, 1, {255, 0, 0, 255, 0, 255, 0, 255});
    const int wraps[3] = {10497, 33071, 33648};  // repeat, clamp, mirrored repeat
    for (int i = 0; i < 3; ++i) {
        const int sampler = b.sampler(fmt::format(
            R"({{"magFilter":9728,"minFilter":9728,"wrapS":{},"wrapT":33071}})", wraps[i]));
        const int material = b.material(
            fmt::format(R"({{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":{}}}}}}})",
                        b.texture(red_green, sampler)));
        b.mesh_node(b.quad(0, 2.0f - 2.0f * float(i), 0, 1.6f, material, 4, "", 2.0f));
    }
    const int linear = b.sampler(R"({"magFilter":9729,"minFilter":9729})");
    const int blended = b.material(
        fmt::format(R"({{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":{}}}}}}})",
                    b.texture(red_green, linear)));
    b.mesh_node(b.quad(3, 0, 0, 3.2f, blended));
    const Scene scene = load(b.json());
    Camera camera;
    camera.position = {0, 0, 10};
    camera.vertical_fov = 0.8f;
    const Frame frame = render(scene, camera);
    const Pinhole pinhole{camera.position, camera.vertical_fov};
    const glm::vec3 red(1, 0, 0), green(0, 1, 0);
    // u at 0.25, 0.75, 1.25, 1.75: texel 0, 1, then by wrap mode.
    const glm::vec3 expected[3][4] = {{red, green, red, green},    // repeat
                                      {red, green, green, green},  // clamp
                                      {red, green, green, red}};   // mirrored
    for (int i = 0; i < 3; ++i) {
        INFO("wrap " << wraps[i]);
        for (int k = 0; k < 4; ++k) {
            const float x = -0.8f + 0.2f + 0.4f * float(k);
            const glm::ivec2 p = pinhole.pixel({x, 2.0f - 2.0f * float(i), 0}, frame.layout);
            CHECK(near(rgb(frame.albedo0, p), expected[i][k], 0.01f));
        }
    }
    // Linear magnification halfway between the texel centres: half of each.
    const glm::ivec2 middle = pinhole.pixel({3, 0, 0}, frame.layout);
    const glm::vec3 mixed = rgb(frame.albedo0, middle);
    CHECK(mixed.r == Approx(0.5f).margin(0.1f));
    CHECK(mixed.g == Approx(0.5f).margin(0.1f));
}

namespace {

// The sample models of Debian's assimp-testmodels (Khronos glTF sample
// models); without the package the test is reported to ctest as skipped.
fs::path sample_model(const std::string& relative) {
    const fs::path path = fs::path(DEEPGI_SAMPLE_MODELS) / relative;
    if (!fs::exists(path))
        spiral::test::skip_test(path.string() +
                                " is absent (install assimp-testmodels: scripts/install-deps.sh)");
    return path;
}

// Where `camera` puts a world point, in internal pixels, from its yaw and
// pitch as scene.hpp defines them and a textbook look-at and perspective.
glm::vec2 project(const Camera& camera, glm::vec3 world, const FrameLayout& layout) {
    const glm::vec3 forward(std::sin(camera.yaw) * std::cos(camera.pitch), std::sin(camera.pitch),
                            -std::cos(camera.yaw) * std::cos(camera.pitch));
    const glm::mat4 view = glm::lookAt(camera.position, camera.position + forward, {0, 1, 0});
    const glm::mat4 projection = glm::perspective(
        camera.vertical_fov, float(kWidth) / float(kHeight), camera.near_plane, 1e4f);
    const glm::vec4 clip = projection * view * glm::vec4(world, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {float(layout.guard) + (ndc.x * 0.5f + 0.5f) * kWidth,
            float(layout.guard) + (ndc.y * 0.5f + 0.5f) * kHeight};
}

}  // namespace

TEST_CASE("gltf render: the 2CylinderEngine sample fills its projected bounding box",
          "[runtime][gltf][render][sample]") {
    const auto path = sample_model("2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
    HeadlessContext context;
    const Scene scene = load_gltf_scene(path);
    // Its bounding box from the file's accessors' own min / max would do too;
    // the vertices' box is what every node transform has been applied to.
    const Frame frame = render(scene, scene.default_camera);
    glm::vec2 low(1e9f), high(-1e9f);
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? scene.bounds.max.x : scene.bounds.min.x,
                          (corner & 2) ? scene.bounds.max.y : scene.bounds.min.y,
                          (corner & 4) ? scene.bounds.max.z : scene.bounds.min.z);
        const glm::vec2 pixel = project(scene.default_camera, p, frame.layout);
        low = glm::min(low, pixel);
        high = glm::max(high, pixel);
    }
    // The viewport part of the box.
    const int g = frame.layout.guard;
    const int x0 = std::max(g, int(std::floor(low.x)) - 1);
    const int y0 = std::max(g, int(std::floor(low.y)) - 1);
    const int x1 = std::min(g + kWidth - 1, int(std::ceil(high.x)) + 1);
    const int y1 = std::min(g + kHeight - 1, int(std::ceil(high.y)) + 1);
    REQUIRE(x1 - x0 > kWidth / 4);
    int inside = 0, outside = 0;
    for (int y = g; y < g + kHeight; ++y) {
        for (int x = g; x < g + kWidth; ++x) {
            if (frame.depth0.at(x, y) <= 0.0f) continue;
            (x >= x0 && x <= x1 && y >= y0 && y <= y1 ? inside : outside) += 1;
        }
    }
    CHECK(outside == 0);
    // An engine is no box, but it fills much of its own.
    CHECK(inside > (x1 - x0 + 1) * (y1 - y0 + 1) * 4 / 10);
}

TEST_CASE("gltf render: the BoxTextured sample shows its texture's colours",
          "[runtime][gltf][render][sample]") {
    const auto path = sample_model("BoxTextured-glTF/BoxTextured.gltf");
    HeadlessContext context;
    const Scene scene = load_gltf_scene(path);
    const Frame frame = render(scene, scene.default_camera);
    // The texture's three commonest colours (quantised to 1/8), decoded here.
    int width = 0, height = 0, channels = 0;
    unsigned char* texels = stbi_load((path.parent_path() / "CesiumLogoFlat.png").string().c_str(),
                                      &width, &height, &channels, 3);
    REQUIRE(texels != nullptr);
    std::map<int, int> histogram;
    std::map<int, glm::vec3> sum;
    for (int i = 0; i < width * height; ++i) {
        const unsigned char* t = texels + 3 * i;
        const int key = (t[0] >> 5) << 6 | (t[1] >> 5) << 3 | (t[2] >> 5);
        ++histogram[key];
        sum[key] += glm::vec3(srgb_to_linear(t[0] / 255.0f), srgb_to_linear(t[1] / 255.0f),
                              srgb_to_linear(t[2] / 255.0f));
    }
    stbi_image_free(texels);
    std::vector<std::pair<int, int>> common;
    for (const auto& [key, count] : histogram) common.push_back({count, key});
    std::sort(common.rbegin(), common.rend());
    REQUIRE(common.size() >= 3);
    int covered = 0;
    for (int y = 0; y < frame.depth0.height; ++y)
        for (int x = 0; x < frame.depth0.width; ++x) covered += frame.depth0.at(x, y) > 0.0f;
    REQUIRE(covered > kWidth * kHeight / 10);
    for (int rank = 0; rank < 3; ++rank) {
        const glm::vec3 colour =
            sum[common[std::size_t(rank)].second] / float(common[std::size_t(rank)].first);
        INFO("texture colour " << colour.r << " " << colour.g << " " << colour.b);
        int matching = 0;
        for (int y = 0; y < frame.albedo0.height; ++y)
            for (int x = 0; x < frame.albedo0.width; ++x)
                if (frame.depth0.at(x, y) > 0.0f && near(rgb(frame.albedo0, {x, y}), colour, 0.06f))
                    ++matching;
        CHECK(matching > covered / 50);
    }
}
