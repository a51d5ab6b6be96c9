// What the glTF loader reads besides geometry: materials (double-sided,
// emissive strength, alpha modes, samplers, metallic and roughness), vertex
// colours, lights, cameras and the view fitted when a file has none, and
// the one summary line naming what it ignores. Each file is crafted here;
// the expected scene or refusal follows from its construction.
#include "crafted_gltf.hpp"
#include "gltf_builder.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/scene.hpp"
#include "../support/gltf_support.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

using deepgi::InputError;
using namespace deepgi::test;

TEST_CASE("gltf loader: the file's first perspective camera is the view, with its node transform",
          "[runtime][gltf]") {
    // Camera 0 is orthographic (ignored); camera 1 sits at (1,2,3) turned +90
    // degrees about +Y, so it looks down -X with +Z on its left and -Z on its
    // right. Camera 2 ("back") is only reachable by --camera.
    TriangleFile file;
    const double s = std::sqrt(0.5);
    file.nodes = fmt::format(R"([{{"mesh":0,"children":[1,2,3]}},{{"camera":0}},)"
                             R"({{"camera":1,"translation":[1,2,3],"rotation":[0,{0},0,{0}]}},)"
                             R"({{"camera":2,"name":"back node","translation":[0,0,5]}}])",
                             s);
    file.extra =
        R"(,"cameras":[{"type":"orthographic","orthographic":{"xmag":1,"ymag":1,"znear":0.1,"zfar":9}},)"
        R"({"type":"perspective","name":"key","perspective":{"yfov":0.7,"znear":0.25}},)"
        R"({"type":"perspective","perspective":{"yfov":1.0,"znear":0.5,"aspectRatio":1.5}}])";
    const deepgi::Scene scene = load(triangle_gltf(file));
    REQUIRE(scene.file_cameras.size() == 2);
    const deepgi::Camera& camera = scene.default_camera;
    CHECK(camera.vertical_fov == Approx(0.7f));
    CHECK(camera.near_plane == Approx(0.25f));
    // Hand-computed view: eye (1,2,3) looking at (0,2,3), up +Y, so right is -Z.
    const glm::mat4 view = deepgi::camera_view_matrix(camera);
    const auto in_view = [&](glm::vec3 world) { return glm::vec3(view * glm::vec4(world, 1)); };
    for (auto [world, expected] : {std::pair{glm::vec3(0, 2, 3), glm::vec3(0, 0, -1)},
                                   std::pair{glm::vec3(1, 2, 2), glm::vec3(1, 0, 0)},
                                   std::pair{glm::vec3(1, 3, 3), glm::vec3(0, 1, 0)}}) {
        const glm::vec3 got = in_view(world);
        for (int axis = 0; axis < 3; ++axis)
            CHECK(got[axis] == Approx(expected[axis]).margin(1e-5));
    }
    CHECK(std::count_if(scene.warnings.begin(), scene.warnings.end(), [](const std::string& w) {
              return w.find("1 orthographic camera") != std::string::npos;
          }) == 1);
    // --camera by name (the node's, as the camera has none) and by file index.
    const deepgi::Camera back = deepgi::find_file_camera(scene, "back node");
    CHECK(back.position == glm::vec3(0, 0, 5));
    CHECK(back.yaw == 0.0f);
    CHECK(deepgi::find_file_camera(scene, "2").near_plane == 0.5f);
    CHECK(deepgi::find_file_camera(scene, "key").near_plane == 0.25f);
    try {
        deepgi::find_file_camera(scene, "0");  // orthographic: not selectable
        FAIL("camera 0 was accepted");
    } catch (const InputError& error) {
        CHECK(std::string(error.what()) ==
              "--camera '0': scene 'crafted.gltf' has no such perspective camera (it has 1 "
              "'key', 2 'back node')");
    }
}

TEST_CASE("gltf loader: a double-sided material gets the back face, wound back, normal flipped",
          "[runtime][gltf]") {
    TriangleFile file;
    file.primitive_extra = R"(,"material":0)";
    file.extra = R"(,"materials":[{"doubleSided":true}])";
    const deepgi::Scene scene = load(triangle_gltf(file));
    REQUIRE(scene.indices.size() == 6);
    const glm::vec3 front[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const glm::vec3 back[3] = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}};  // a, c, b
    for (int k = 0; k < 3; ++k) {
        const auto& f = scene.vertices[scene.indices[std::size_t(k)]];
        const auto& b = scene.vertices[scene.indices[std::size_t(3 + k)]];
        REQUIRE(f.position == front[k]);
        REQUIRE(f.normal == glm::vec3(0, 0, 1));
        REQUIRE(b.position == back[k]);
        REQUIRE(b.normal == glm::vec3(0, 0, -1));
    }
    // Single-sided (the default) stays one face.
    file.extra = R"(,"materials":[{"doubleSided":false}])";
    REQUIRE(load(triangle_gltf(file)).indices.size() == 3);
}

TEST_CASE("gltf loader: emissive strength scales the factor, BLEND is opaque with one warning",
          "[runtime][gltf]") {
    TriangleFile file;
    file.primitive_extra = R"(,"material":0)";
    file.extra =
        R"(,"extensionsUsed":["KHR_materials_emissive_strength"],"materials":[{"emissiveFactor":[0.5,0.25,1],)"
        R"("alphaMode":"BLEND","extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":4}}}])";
    const deepgi::Scene scene = load(triangle_gltf(file));
    REQUIRE(scene.materials.size() == 1);
    REQUIRE(scene.materials[0].emissive == glm::vec3(2.0f, 1.0f, 4.0f));
    REQUIRE(std::count(scene.warnings.begin(), scene.warnings.end(),
                       "1 material(s) with alphaMode BLEND are rendered opaque") == 1);
    // The extension is used, so it is not listed as ignored.
    for (const auto& warning : scene.warnings) REQUIRE(!contains(warning, "ignored"));
    file.extra =
        R"(,"materials":[{"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":-1}}}])";
    REQUIRE(contains(refusal(triangle_gltf(file)),
                     "material 0: emissiveStrength must be a finite number >= 0"));
}

TEST_CASE("gltf loader: everything ignored is named in one summary line", "[runtime][gltf]") {
    TriangleFile file;
    file.primitive_extra = R"(,"material":0)";
    file.extra =
        R"(,"extensionsUsed":["KHR_texture_transform","KHR_lights_punctual"],)"
        R"("skins":[{"joints":[0]},{"joints":[0]}],)"
        R"("animations":[{"channels":[{"sampler":0,"target":{"node":0,"path":"translation"}}],)"
        R"("samplers":[{"input":0,"output":0}]}],)"
        R"("materials":[{"alphaMode":"MASK","normalTexture":{"index":0}}])";
    // MASK, COLOR_0 and emissive textures are read, so they are not listed;
    // normal textures are skipped (no tangents in the G-buffer) and are.
    const deepgi::Scene scene = load(triangle_gltf(file));
    std::vector<std::string> summaries;
    for (const auto& warning : scene.warnings)
        if (contains(warning, "ignored")) summaries.push_back(warning);
    REQUIRE(summaries ==
            std::vector<std::string>{
                "ignored: 2 skins, 1 animation, 1 normal texture, KHR_texture_transform"});
    // A file using only what is read has no summary.
    for (const auto& warning : load(triangle_gltf({})).warnings)
        REQUIRE(!contains(warning, "ignored"));
}

TEST_CASE("gltf loader: the first light met is the key light, the rest dropped",
          "[runtime][gltf]") {
    // Visited first, node 2: spot light 1 at (0,4,0) turned -90 degrees about
    // +X, so its -Z points down -Y. Then node 1: point light 0; node 3: sun 2.
    TriangleFile file;
    const double s = std::sqrt(0.5);
    file.nodes = fmt::format(R"([{{"mesh":0,"children":[2,1,3]}},)"
                             R"({{"extensions":{{"KHR_lights_punctual":{{"light":0}}}}}},)"
                             R"({{"translation":[0,4,0],"rotation":[{0},0,0,{1}],)"
                             R"("extensions":{{"KHR_lights_punctual":{{"light":1}}}}}},)"
                             R"({{"extensions":{{"KHR_lights_punctual":{{"light":2}}}}}}])",
                             -s, s);
    file.extra =
        R"(,"extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":{"lights":[)"
        R"({"type":"point","name":"bulb","intensity":10},)"
        R"({"type":"spot","name":"lamp","intensity":1366,"color":[1,0.5,0.25],)"
        R"("spot":{"innerConeAngle":0.25,"outerConeAngle":0.5}},)"
        R"({"type":"directional","name":"sun","intensity":683}]}})";
    const deepgi::Scene scene = load(triangle_gltf(file));
    const deepgi::KeyLight& key = scene.key_light;
    CHECK(key.kind == deepgi::LightKind::spot);
    CHECK(key.position.y == Approx(4.0f));
    CHECK(key.direction.x == Approx(0.0f).margin(1e-6));
    CHECK(key.direction.y == Approx(-1.0f));
    CHECK(key.direction.z == Approx(0.0f).margin(1e-6));
    CHECK(key.intensity == Approx(2.0f));  // 1366 cd / 683 lm/W
    CHECK(key.colour == glm::vec3(1.0f, 0.5f, 0.25f));
    CHECK(key.inner_cone == 0.25f);
    CHECK(key.outer_cone == 0.5f);
    CHECK(std::count(scene.warnings.begin(), scene.warnings.end(),
                     "dropped lights: 0 'bulb' (point, one key light only), 2 'sun' "
                     "(directional, one key light only)") == 1);
    for (const auto& warning : scene.warnings) CHECK(!contains(warning, "ignored"));
}

TEST_CASE("gltf loader: a point light first in the file is the key light, with its range",
          "[runtime][gltf]") {
    auto file_with = [](const std::string& light) {
        TriangleFile file;
        file.nodes = R"([{"mesh":0,"children":[1,2]},)"
                     R"({"translation":[1,2,3],"extensions":{"KHR_lights_punctual":{"light":0}}},)"
                     R"({"extensions":{"KHR_lights_punctual":{"light":1}}}])";
        file.extra =
            R"(,"extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":{"lights":[)" +
            light + R"(,{"type":"area"}]}})";
        return triangle_gltf(file);
    };
    const deepgi::Scene scene =
        load(file_with(R"({"type":"point","name":"bulb","intensity":1366,"range":5})"));
    const deepgi::KeyLight& key = scene.key_light;
    CHECK(key.kind == deepgi::LightKind::point);
    CHECK(key.position == glm::vec3(1, 2, 3));
    CHECK(key.intensity == Approx(2.0f));  // 1366 cd / 683 lm/W
    CHECK(key.range == 5.0f);
    // The area light is dropped, and nothing else is said about lights.
    CHECK(std::count(scene.warnings.begin(), scene.warnings.end(),
                     "dropped lights: 1 (area: unknown type)") == 1);
    for (const auto& warning : scene.warnings)
        CHECK((warning.find("light") == std::string::npos || warning.starts_with("dropped")));
    CHECK(load(file_with(R"({"type":"point"})")).key_light.range == 0.0f);
    CHECK(contains(refusal(file_with(R"({"type":"point","range":-1})")),
                   "light 0: range must be a finite number > 0"));
}

TEST_CASE("gltf loader: COLOR_0 is read as float or normalised integers, other forms refused",
          "[runtime][gltf]") {
    // A quad (4 vertices) whose COLOR_0 repeats one colour given as `values`.
    auto quad_with = [](auto values, int component_type, const std::string& type, bool normalized,
                        int count = 4) {
        GltfBuilder b;
        const int colours = b.accessor(values, component_type, type, count, normalized);
        b.mesh_node(b.quad(0, 0, 0, 1, -1, 4, fmt::format(R"(,"COLOR_0":{})", colours)));
        return b.json();
    };
    auto repeated = [](auto one) {
        std::vector<typename decltype(one)::value_type> all;
        for (int v = 0; v < 4; ++v) all.insert(all.end(), one.begin(), one.end());
        return all;
    };
    const auto floats = repeated(std::vector<float>{0.25f, 0.5f, 1.0f});
    const auto bytes = repeated(std::vector<std::uint8_t>{255, 0, 51, 102});
    const auto shorts = repeated(std::vector<std::uint16_t>{65535, 0, 13107, 0});
    auto colours = [](const deepgi::Scene& scene) {
        std::vector<glm::vec4> list;
        for (const auto& vertex : scene.vertices) list.push_back(vertex.colour);
        return list;
    };
    using V = std::vector<glm::vec4>;
    CHECK(colours(load(quad_with(floats, 5126, "VEC3", false))) ==
          V(6, glm::vec4(0.25f, 0.5f, 1.0f, 1.0f)));
    CHECK(colours(load(quad_with(bytes, 5121, "VEC4", true))) ==
          V(6, glm::vec4(1.0f, 0.0f, 0.2f, 0.4f)));
    CHECK(colours(load(quad_with(shorts, 5123, "VEC4", true))) ==
          V(6, glm::vec4(1.0f, 0.0f, 0.2f, 0.0f)));
    // Without COLOR_0 the colour is white.
    GltfBuilder plain;
    plain.mesh_node(plain.quad(0, 0, 0, 1, -1));
    CHECK(colours(load(plain.json())) == V(6, glm::vec4(1.0f)));
    // Integers not normalised, signed, or two components: refused naming the accessor.
    const std::string message =
        "COLOR_0 (accessor 0) must be VEC3 or VEC4 of float, or of normalized unsigned byte or "
        "short";
    CHECK(contains(refusal(quad_with(bytes, 5121, "VEC4", false)), message));
    CHECK(contains(refusal(quad_with(bytes, 5120, "VEC4", true)), message));
    CHECK(contains(refusal(quad_with(floats, 5126, "VEC2", false, 4)), message));
    CHECK(contains(refusal(quad_with(floats, 5126, "VEC3", false, 3)),
                   "COLOR_0 and POSITION counts differ"));
    auto not_finite = floats;
    not_finite[4] = std::numeric_limits<float>::quiet_NaN();
    CHECK(contains(refusal(quad_with(not_finite, 5126, "VEC3", false)),
                   "a COLOR_0 value is not finite"));
    GltfBuilder dangling;
    dangling.mesh_node(dangling.quad(0, 0, 0, 1, -1, 4, R"(,"COLOR_0":99)"));
    CHECK(contains(refusal(dangling.json()), "accessor index out of range"));
}

TEST_CASE("gltf loader: alpha modes, cutoffs and samplers are read, bad values refused",
          "[runtime][gltf]") {
    auto with_material = [](const std::string& material, const std::string& sampler = "") {
        GltfBuilder b;
        const int s = sampler.empty() ? -1 : b.sampler(sampler);
        const int texture = b.texture(encode_png(1, 1, {10, 20, 30, 40}), s);
        const int m = b.material(
            fmt::format(R"({{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":{}}}}},)"
                        R"("emissiveTexture":{{"index":{}}}{}}})",
                        texture, texture, material));
        b.mesh_node(b.quad(0, 0, 0, 1, m));
        return b.json();
    };
    const deepgi::Scene masked = load(with_material(R"(,"alphaMode":"MASK","alphaCutoff":0.3)"));
    REQUIRE(masked.materials.size() == 1);
    CHECK(masked.materials[0].alpha_cutoff == 0.3f);
    CHECK(masked.materials[0].base_colour_texture == 0);
    CHECK(masked.materials[0].emissive_texture == 0);  // one image, uploaded once
    CHECK(masked.textures.size() == 1);
    // MASK without a cutoff: the specification's 0.5. OPAQUE: no mask.
    CHECK(load(with_material(R"(,"alphaMode":"MASK")")).materials[0].alpha_cutoff == 0.5f);
    CHECK(load(with_material("")).materials[0].alpha_cutoff < 0.0f);
    CHECK(contains(refusal(with_material(R"(,"alphaMode":"MASK","alphaCutoff":-1)")),
                   "material 0: alphaCutoff must be a finite number >= 0"));
    CHECK(contains(refusal(with_material(R"(,"alphaMode":"CUTOUT")")),
                   "material 0: alphaMode 'CUTOUT' is not OPAQUE, MASK or BLEND"));

    // No sampler: trilinear, repeat. A sampler: its values, for both textures.
    const deepgi::TextureSampler defaults =
        load(with_material("")).materials[0].base_colour_sampler;
    CHECK(defaults == deepgi::TextureSampler{0x2601, 0x2703, 0x2901, 0x2901});
    const deepgi::Scene sampled = load(
        with_material("", R"({"magFilter":9728,"minFilter":9984,"wrapS":33071,"wrapT":33648})"));
    const deepgi::TextureSampler expected{9728, 9984, 33071, 33648};
    CHECK(sampled.materials[0].base_colour_sampler == expected);
    CHECK(sampled.materials[0].emissive_sampler == expected);
    CHECK(contains(refusal(with_material("", R"({"magFilter":9984})")),
                   "sampler 0: magFilter 9984 is not a valid value"));
    CHECK(contains(refusal(with_material("", R"({"minFilter":1})")),
                   "sampler 0: minFilter 1 is not a valid value"));
    CHECK(contains(refusal(with_material("", R"({"wrapS":9728})")),
                   "sampler 0: wrapS 9728 is not a valid value"));
    CHECK(contains(refusal(with_material("", R"({"wrapT":0})")),
                   "sampler 0: wrapT 0 is not a valid value"));
    // A texture naming a sampler that is not there.
    std::string missing = with_material("");
    const std::string source = R"({"source":0})";
    missing.replace(missing.find(source), source.size(), R"({"source":0,"sampler":3})");
    CHECK(contains(refusal(missing), "texture 0: sampler index out of range"));
}

TEST_CASE("gltf loader: a file without a camera gets a three-quarter view fitted to its bounds",
          "[runtime][gltf]") {
    const deepgi::Scene scene = load(five_vertex_gltf({5}));
    const deepgi::Camera& camera = scene.default_camera;
    const glm::vec3 forward = deepgi::camera_forward(camera);
    // Neither head-on nor level: the view comes from off every axis.
    const float down = glm::degrees(std::asin(-forward.y));
    const float round = glm::degrees(std::atan2(std::abs(forward.x), std::abs(forward.z)));
    CHECK(down >= 20.0f);
    CHECK(down <= 45.0f);
    CHECK(round >= 25.0f);
    CHECK(round <= 65.0f);
    // Every corner of the bounds lies in front of the camera and inside a
    // 16:9 frame, by a textbook perspective projection of the camera's view.
    const glm::mat4 projection = glm::perspective(camera.vertical_fov, 16.0f / 9.0f, 1e-3f, 1e3f);
    const glm::mat4 view = glm::lookAt(camera.position, camera.position + forward, {0, 1, 0});
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? scene.bounds.max.x : scene.bounds.min.x,
                          (corner & 2) ? scene.bounds.max.y : scene.bounds.min.y,
                          (corner & 4) ? scene.bounds.max.z : scene.bounds.min.z);
        const glm::vec4 clip = projection * view * glm::vec4(p, 1.0f);
        INFO("corner " << corner);
        REQUIRE(clip.w > 0.0f);
        CHECK(std::abs(clip.x / clip.w) <= 1.0f);
        CHECK(std::abs(clip.y / clip.w) <= 1.0f);
    }
}

TEST_CASE("gltf loader: metallic and roughness factors are kept, with glTF's defaults",
          "[runtime][gltf]") {
    // The mirror test (docs/reflections.md) reads them: roughness at most
    // --mirror-roughness and metallic at least 0.5.
    TriangleFile file;
    file.primitive_extra = R"(,"material":0)";
    file.extra =
        R"(,"materials":[{"pbrMetallicRoughness":{"roughnessFactor":0.05,"metallicFactor":0.75}}])";
    const deepgi::Scene polished = load(triangle_gltf(file));
    REQUIRE(polished.materials.size() == 1);
    REQUIRE(polished.materials[0].roughness == 0.05f);
    REQUIRE(polished.materials[0].metallic == 0.75f);
    file.extra = R"(,"materials":[{}])";
    const deepgi::Scene plain = load(triangle_gltf(file));
    REQUIRE(plain.materials[0].roughness == 1.0f);
    REQUIRE(plain.materials[0].metallic == 1.0f);
}
