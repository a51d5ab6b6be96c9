// The glTF loader's file handling and geometry: hostile files (offsets and
// counts that wrap, deep JSON, node graphs that multiply work, huge
// textures), limits, files recognised by content, and primitives turned
// into triangles. Each file is crafted here; the expected scene or refusal
// follows from its construction.
#include "crafted_gltf.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/scene.hpp"
#include "../support/gltf_support.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;
using deepgi::InputError;
using deepgi::SceneLimits;
using namespace deepgi::test;

namespace {

// A GLB container around `json`: 12-byte header, then one JSON chunk padded
// with spaces to 4 bytes (the buffer stays a data URI inside the JSON).
std::string glb_of(std::string json) {
    while (json.size() % 4 != 0) json += ' ';
    std::vector<std::uint8_t> bytes;
    append(bytes, std::uint32_t(0x46546C67));  // "glTF"
    append(bytes, std::uint32_t(2));
    append(bytes, std::uint32_t(12 + 8 + json.size()));
    append(bytes, std::uint32_t(json.size()));
    append(bytes, std::uint32_t(0x4E4F534A));  // "JSON"
    bytes.insert(bytes.end(), json.begin(), json.end());
    return std::string(bytes.begin(), bytes.end());
}

std::string load_scene_refusal(const fs::path& path) {
    try {
        deepgi::load_scene(path.string());
    } catch (const InputError& error) {
        return error.what();
    }
    return "";
}

}  // namespace

TEST_CASE("gltf loader: the crafted triangle loads as built", "[runtime][gltf]") {
    const deepgi::Scene scene = load(triangle_gltf({}));
    REQUIRE(scene.indices.size() == 3);
    REQUIRE(scene.vertices.size() == 3);
    REQUIRE(scene.vertices[0].position == glm::vec3(0, 0, 0));
    REQUIRE(scene.vertices[1].position == glm::vec3(1, 0, 0));
    REQUIRE(scene.vertices[2].position == glm::vec3(0, 1, 0));
    TriangleFile no_indices;
    no_indices.with_indices = false;
    REQUIRE(load(triangle_gltf(no_indices)).vertices.size() == 3);
}

TEST_CASE("gltf loader: offsets and counts that wrap 64 bits are refused naming the accessor",
          "[runtime][gltf]") {
    TriangleFile offset;  // 2^64 - 4: begin + span wraps to a small number
    offset.position_fields = R"("count":3,"byteOffset":18446744073709551612)";
    const std::string offset_error = refusal(triangle_gltf(offset));
    INFO(offset_error);
    REQUIRE(contains(offset_error, "accessor 0"));

    TriangleFile indices;  // 2^62 + 3 four-byte indices: (count - 1) * 4 wraps
    indices.index_fields = R"("count":4611686018427387907)";
    const std::string index_error = refusal(triangle_gltf(indices));
    INFO(index_error);
    REQUIRE(contains(index_error, "accessor 1"));
    REQUIRE(contains(index_error, "overflows"));

    TriangleFile positions;  // the same count on the positions, drawn without indices
    positions.with_indices = false;
    positions.position_fields = R"("count":4611686018427387907)";
    const std::string position_error = refusal(triangle_gltf(positions));
    INFO(position_error);
    REQUIRE(contains(position_error, "accessor 0"));
    REQUIRE(contains(position_error, "overflows"));

    TriangleFile past_end;  // one element too many, no overflow: the plain bound
    past_end.position_fields = R"("count":4)";
    REQUIRE(contains(refusal(triangle_gltf(past_end)), "past the end of its buffer view"));

    TriangleFile short_stride;  // elements overlapping within a 4-byte stride
    std::string json = triangle_gltf(short_stride);
    const std::string view = R"({"buffer":0,"byteLength":36})";
    json.replace(json.find(view), view.size(), R"({"buffer":0,"byteLength":36,"byteStride":4})");
    REQUIRE(contains(refusal(json), "byteStride 4 is smaller than one element"));
}

TEST_CASE("gltf loader: 32-bit indices are read as integers, not through float",
          "[runtime][gltf]") {
    // Found by the fuzzer: index 0xffffffff became the float 2^32, whose
    // conversion back to uint32 is undefined (0 on x86: a silent, wrong
    // triangle). Read exactly, it is past the vertices and refused.
    std::string json = triangle_gltf({});
    std::vector<std::uint8_t> buffer;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) append(buffer, v);
    for (std::uint32_t i : {0u, 1u, 0xffffffffu}) append(buffer, i);
    const std::size_t start = json.find("base64,") + 7;
    json.replace(start, json.find('"', start) - start, base64(buffer));
    REQUIRE(refusal(json).find("refers past the end of the vertices") != std::string::npos);
}

TEST_CASE("gltf loader: JSON nested 20,000 deep is refused before parsing", "[runtime][gltf]") {
    // Through a file too, since the file path reads the text itself.
    const fs::path dir = fs::temp_directory_path() / fmt::format("gltf-deep-{}", ::getpid());
    fs::create_directories(dir);
    std::ofstream(dir / "deep.gltf") << deep_json(20000);
    std::string message;
    try {
        deepgi::load_gltf_scene(dir / "deep.gltf");
    } catch (const InputError& error) {
        message = error.what();
    }
    fs::remove_all(dir);
    REQUIRE(contains(message, "JSON nests deeper than 128 levels"));
    REQUIRE(contains(message, "json-depth"));
    // Brackets inside strings are text, not nesting.
    TriangleFile quoted;
    quoted.extra = R"(,"extras":{"text":")" + std::string(1000, '[') + R"(\"["})";
    REQUIRE(load(triangle_gltf(quoted)).indices.size() == 3);
    // deep_json(127) nests 129 levels (the document and asset objects count):
    // refused by default, parsed (and found empty) once the limit is 129.
    SceneLimits raised;
    raised.json_depth = 129;
    REQUIRE(contains(refusal(deep_json(127)), "deeper than 128"));
    REQUIRE(contains(refusal(deep_json(127), raised), "no triangles"));
}

TEST_CASE("gltf loader: node graphs that share children are bounded by visits and triangles",
          "[runtime][gltf]") {
    TriangleFile dag;
    dag.nodes = dag_nodes(10);  // 2^10 instances of the triangle in 2^11 - 1 visits
    const deepgi::Scene scene = load(triangle_gltf(dag));
    REQUIRE(scene.indices.size() == 3 * 1024);

    SceneLimits visits;
    visits.node_visits = 2046;
    REQUIRE(contains(refusal(triangle_gltf(dag), visits), "more than 2046 node visits"));
    visits.node_visits = 2047;
    REQUIRE(refusal(triangle_gltf(dag), visits).empty());

    SceneLimits triangles;
    triangles.triangles = 1023;
    REQUIRE(contains(refusal(triangle_gltf(dag), triangles), "more than 1023 triangles"));

    for (int levels : {20, 40}) {  // 2^20 and 2^40 instances: refused at the default limits
        dag.nodes = dag_nodes(levels);
        const std::string message = refusal(triangle_gltf(dag));
        INFO(message);
        REQUIRE(contains(message, "instances"));  // 100,000 come before 1,000,000 visits
        SceneLimits many_instances;
        many_instances.instances = 1ull << 50;
        const std::string visits_message = refusal(triangle_gltf(dag), many_instances);
        INFO(visits_message);
        REQUIRE(contains(visits_message, "node-visits"));
    }
}

TEST_CASE("gltf loader: texture size and decoded bytes are limited before decoding",
          "[runtime][gltf]") {
    // 3x2 RGBA pixels; the loaded texture must hold exactly these bytes.
    std::vector<std::uint8_t> rgba;
    for (int i = 0; i < 24; ++i) rgba.push_back(std::uint8_t(i * 10 + 5));
    const auto png = encode_png(3, 2, rgba);
    TriangleFile textured;
    textured.primitive_extra = R"(,"material":0)";
    textured.extra = image_members({png});
    const deepgi::Scene scene = load(triangle_gltf(textured));
    REQUIRE(scene.textures.size() == 1);
    REQUIRE(scene.textures[0].width == 3);
    REQUIRE(scene.textures[0].height == 2);
    REQUIRE(scene.textures[0].rgba8.size() == rgba.size());
    for (std::size_t i = 0; i < rgba.size(); ++i)
        REQUIRE(scene.textures[0].rgba8[i] == rgba[i]);  // alpha too: it feeds the mask

    SceneLimits side;
    side.texture_side = 2;
    REQUIRE(contains(refusal(triangle_gltf(textured), side),
                     "image 0 is 3x2 pixels, above the limit of 2 per side"));

    // A 16384x16384 PNG header: refused from its header, before any decoding.
    textured.extra = image_members({png_header(16384, 16384)});
    const std::string huge = refusal(triangle_gltf(textured));
    INFO(huge);
    REQUIRE(contains(huge, "16384x16384"));
    REQUIRE(contains(huge, "texture-side"));

    // Two 3x2 images are 48 decoded bytes: 47 refuses the second.
    textured.extra = image_members({png, png});
    SceneLimits bytes;
    bytes.texture_bytes = 47;
    REQUIRE(contains(refusal(triangle_gltf(textured), bytes), "image 1 brings"));
    bytes.texture_bytes = 48;
    REQUIRE(refusal(triangle_gltf(textured), bytes).empty());
}

TEST_CASE("gltf loader: bytes from memory never reach the file system", "[runtime][gltf]") {
    // The triangle's buffer as a file beside the JSON.
    const fs::path dir = fs::temp_directory_path() / fmt::format("gltf-external-{}", ::getpid());
    fs::create_directories(dir);
    std::string json = triangle_gltf({});
    const std::size_t uri = json.find("data:application");
    const std::size_t uri_end = json.find('"', uri);
    const std::string payload = json.substr(uri, uri_end - uri);
    std::vector<std::uint8_t> bytes;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) append(bytes, v);
    for (std::uint32_t i : {0u, 1u, 2u}) append(bytes, i);
    std::ofstream(dir / "triangle.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    json.replace(uri, payload.size(), "triangle.bin");
    std::ofstream(dir / "external.gltf") << json;
    // From a file, external buffers are the format's normal case...
    const std::size_t from_file = deepgi::load_gltf_scene(dir / "external.gltf").indices.size();
    // ...from memory (the fuzzer's and a server's entry) they are refused.
    const std::string message = refusal(json);
    fs::remove_all(dir);
    REQUIRE(from_file == 3);
    REQUIRE(!message.empty());
}

TEST_CASE("gltf loader: scene limits parse as NAME=VALUE", "[runtime][gltf]") {
    SceneLimits limits;
    deepgi::set_scene_limit(limits, "triangles=5");
    deepgi::set_scene_limit(limits, "json-depth=7");
    deepgi::set_scene_limit(limits, "texture-bytes=18446744073709551615");
    REQUIRE(limits.triangles == 5);
    REQUIRE(limits.json_depth == 7);
    REQUIRE(limits.texture_bytes == 18446744073709551615ull);
    for (const char* bad : {"triangles", "triangles=", "triangles=0", "triangles=-1",
                            "triangles=1e6", "colours=3", "texture-side=18446744073709551616"})
        REQUIRE_THROWS_AS(deepgi::set_scene_limit(limits, bad), InputError);
}

TEST_CASE("gltf loader: scene files are recognised by content, not by name", "[runtime][gltf]") {
    const fs::path dir = fs::temp_directory_path() / fmt::format("gltf-sniff-{}", ::getpid());
    fs::create_directories(dir);
    auto write = [&](const char* name, const std::string& content) {
        std::ofstream(dir / name, std::ios::binary) << content;
        return dir / name;
    };
    const std::string json = triangle_gltf({});
    REQUIRE(glb_of(json).substr(0, 4) == "glTF");
    const fs::path passwd = write("passwd", "root:x:0:0:root:/root:/bin/sh\n");
    const fs::path text_named_gltf = write("notes.gltf", "hello\n");
    const fs::path upper_json = write("UPPER.GLTF", json);
    const fs::path upper_glb = write("UPPER.GLB", glb_of(json));
    const fs::path glb_as_gltf = write("binary.gltf", glb_of(json));  // the magic decides
    const fs::path glb_as_bin = write("model.bin", glb_of(json));
    const fs::path json_no_extension = write("model", "\xEF\xBB\xBF \n" + json);

    CHECK(contains(load_scene_refusal(passwd), "is not a glTF file"));
    CHECK(contains(load_scene_refusal(text_named_gltf), "is not a glTF file"));
    CHECK(contains(load_scene_refusal(dir / "missing.GLB"), "does not exist"));
    CHECK(contains(load_scene_refusal(dir / "no_such_scene_name"), "unknown scene"));
    for (const fs::path& path :
         {upper_json, upper_glb, glb_as_gltf, glb_as_bin, json_no_extension}) {
        INFO(path.filename().string());
        CHECK(deepgi::load_scene(path.string()).indices.size() == 3);
    }
    fs::remove_all(dir);
}

TEST_CASE("gltf loader: strips and fans become triangles with the specification's winding",
          "[runtime][gltf]") {
    // Strip 0 1 2 3 4 by hand: (0,1,2) (1,3,2) (2,3,4), the odd one swapped.
    // Fan 0 1 2 3 4 by hand: (1,2,0) (2,3,0) (3,4,0).
    const glm::vec3 v[5] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}};
    const int expected[6][3] = {{0, 1, 2}, {1, 3, 2}, {2, 3, 4}, {1, 2, 0}, {2, 3, 0}, {3, 4, 0}};
    // The strip stays counter-clockwise seen from +z (the odd swap at work);
    // the fan's (2,3,0) turns clockwise, as v1..v4 do not circle v0 in order.
    const float facing[6] = {1, 1, 1, 1, -1, 1};
    const deepgi::Scene scene = load(five_vertex_gltf({5, 6}));
    REQUIRE(scene.indices.size() == 18);
    REQUIRE(scene.warnings ==
            std::vector<std::string>{"the file has no perspective camera; using a fitted view"});
    for (int t = 0; t < 6; ++t) {
        for (int k = 0; k < 3; ++k) {
            INFO("triangle " << t << " corner " << k);
            const auto& vertex = scene.vertices[scene.indices[std::size_t(3 * t + k)]];
            REQUIRE(vertex.position == v[expected[t][k]]);
            // Flat normals follow the winding: cross(b - a, c - a) by hand.
            REQUIRE(vertex.normal == glm::vec3(0, 0, facing[t]));
        }
    }
}

TEST_CASE("gltf loader: points and lines are skipped with one warning giving the count",
          "[runtime][gltf]") {
    // Points, lines, line loop and line strip, then a fan that is rendered.
    const deepgi::Scene scene = load(five_vertex_gltf({0, 1, 2, 3, 6}));
    REQUIRE(scene.indices.size() == 9);  // the fan's three triangles only
    REQUIRE(std::count(scene.warnings.begin(), scene.warnings.end(),
                       "skipped 4 point or line primitive(s): they are not surfaces") == 1);
    REQUIRE(scene.warnings.size() == 2);  // and the fitted view's
    REQUIRE(refusal(five_vertex_gltf({0, 3})) ==
            "glTF file 'crafted.gltf': contains no triangles (only 2 point or line primitives)");
    REQUIRE(contains(refusal(five_vertex_gltf({7})), "primitive mode 7 is not supported"));
}
