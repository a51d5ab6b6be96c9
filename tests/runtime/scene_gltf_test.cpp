// The glTF loader against hostile files: wrapping offsets and counts, deep
// JSON, node graphs that multiply work, and huge textures. Each file is
// crafted here; the expected scene or refusal follows from its construction.
#include "deepgi/errors.hpp"
#include "deepgi/scene.hpp"
#include "gltf_support.hpp"

#include <catch2/catch.hpp>
#include <stb_image_write.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using deepgi::InputError;
using deepgi::SceneLimits;
using namespace deepgi::test;

namespace {

deepgi::Scene load(const std::string& json, const SceneLimits& limits = {}) {
    return deepgi::load_gltf_scene_from_memory(
        {reinterpret_cast<const std::uint8_t*>(json.data()), json.size()}, false, "crafted.gltf",
        limits);
}

// The loader's message for `json`, or "" when it loads.
std::string refusal(const std::string& json, const SceneLimits& limits = {}) {
    try {
        load(json, limits);
    } catch (const InputError& error) {
        return error.what();
    }
    return "";
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

std::vector<std::uint8_t> encode_png(int width, int height, const std::vector<std::uint8_t>& rgba) {
    std::vector<std::uint8_t> png;
    auto sink = [](void* context, void* data, int size) {
        auto& out = *static_cast<std::vector<std::uint8_t>*>(context);
        out.insert(out.end(), static_cast<std::uint8_t*>(data),
                   static_cast<std::uint8_t*>(data) + size);
    };
    REQUIRE(stbi_write_png_to_func(sink, &png, width, height, 4, rgba.data(), width * 4) != 0);
    return png;
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

    for (int levels : {20, 40}) {  // 2^20 and 2^40 instances: refused at the default limit
        dag.nodes = dag_nodes(levels);
        const std::string message = refusal(triangle_gltf(dag));
        INFO(message);
        REQUIRE(contains(message, "node-visits"));
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
        REQUIRE(scene.textures[0].rgba8[i] == ((i % 4 == 3) ? 255 : rgba[i]));

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
