// Writes the fuzzer's seed corpus (tests/fuzz/corpus): valid files and every
// hostile case the loader's tests cover, built by the same functions. Run
// once when a case is added: make_corpus <directory>.
#include "../support/gltf_support.hpp"

#include <stb_image_write.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace deepgi::test;

namespace {

void save(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

// The JSON inside a GLB container, with the triangle's buffer as the binary
// chunk instead of a data URI.
std::string glb(const std::string& json, const std::vector<std::uint8_t>& binary) {
    std::string padded_json = json;
    while (padded_json.size() % 4) padded_json += ' ';
    std::vector<std::uint8_t> bin = binary;
    while (bin.size() % 4) bin.push_back(0);
    std::vector<std::uint8_t> out;
    const std::uint32_t total =
        12 + 8 + std::uint32_t(padded_json.size()) + 8 + std::uint32_t(bin.size());
    out.reserve(total);
    for (std::uint32_t v : {0x46546c67u, 2u, total, std::uint32_t(padded_json.size()), 0x4e4f534au})
        append(out, v);
    out.insert(out.end(), padded_json.begin(), padded_json.end());
    for (std::uint32_t v : {std::uint32_t(bin.size()), 0x004e4942u}) append(out, v);
    out.insert(out.end(), bin.begin(), bin.end());
    return std::string(out.begin(), out.end());
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) return 2;
    const std::filesystem::path dir(argv[1]);
    std::filesystem::create_directories(dir);
    save(dir / "valid-triangle.gltf", triangle_gltf({}));
    TriangleFile no_indices;
    no_indices.with_indices = false;
    save(dir / "valid-no-indices.gltf", triangle_gltf(no_indices));
    TriangleFile dag;
    dag.nodes = dag_nodes(6);
    save(dir / "valid-dag-64.gltf", triangle_gltf(dag));
    std::vector<std::uint8_t> rgba;
    for (int i = 0; i < 16; ++i) rgba.push_back(std::uint8_t(i * 16));
    std::vector<std::uint8_t> png;
    stbi_write_png_to_func(
        [](void* c, void* d, int n) {
            auto& o = *static_cast<std::vector<std::uint8_t>*>(c);
            o.insert(o.end(), static_cast<std::uint8_t*>(d), static_cast<std::uint8_t*>(d) + n);
        },
        &png, 2, 2, 4, rgba.data(), 8);
    TriangleFile textured;
    textured.primitive_extra = R"(,"material":0)";
    textured.extra = image_members({png});
    save(dir / "valid-textured.gltf", triangle_gltf(textured));
    {
        std::vector<std::uint8_t> buffer;
        for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) append(buffer, v);
        for (std::uint32_t i : {0u, 1u, 2u}) append(buffer, i);
        std::string json = triangle_gltf({});
        const std::size_t uri = json.find(R"(,"uri")");
        json.erase(uri, json.find('}', uri) - uri);
        save(dir / "valid-triangle.glb", glb(json, buffer));
    }
    TriangleFile offset;
    offset.position_fields = R"("count":3,"byteOffset":18446744073709551612)";
    save(dir / "huge-byteoffset.gltf", triangle_gltf(offset));
    TriangleFile indices;
    indices.index_fields = R"("count":4611686018427387907)";
    save(dir / "huge-index-count.gltf", triangle_gltf(indices));
    TriangleFile positions;
    positions.with_indices = false;
    positions.position_fields = R"("count":4611686018427387907)";
    save(dir / "huge-position-count.gltf", triangle_gltf(positions));
    save(dir / "deep-json-20000.gltf", deep_json(20000));
    dag.nodes = dag_nodes(20);
    save(dir / "dag-2-20.gltf", triangle_gltf(dag));
    dag.nodes = dag_nodes(40);
    save(dir / "dag-2-40.gltf", triangle_gltf(dag));
    textured.extra = image_members({png_header(16384, 16384)});
    save(dir / "png-16384.gltf", triangle_gltf(textured));
    return 0;
}
