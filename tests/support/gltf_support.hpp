#pragma once
// Crafted glTF files for the loader's tests, its fuzzer's seed corpus and its
// benchmark: each built from plain numbers, so the expected scene (or the
// expected refusal) follows from the construction, not from the loader.
#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace deepgi::test {

inline std::string base64(const std::vector<std::uint8_t>& bytes) {
    static const char alphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string text;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t a = bytes[i];
        const std::uint32_t b = i + 1 < bytes.size() ? bytes[i + 1] : 0;
        const std::uint32_t c = i + 2 < bytes.size() ? bytes[i + 2] : 0;
        const std::uint32_t word = a << 16 | b << 8 | c;
        text += alphabet[word >> 18 & 63];
        text += alphabet[word >> 12 & 63];
        text += i + 1 < bytes.size() ? alphabet[word >> 6 & 63] : '=';
        text += i + 2 < bytes.size() ? alphabet[word & 63] : '=';
    }
    return text;
}

template <typename T>
void append(std::vector<std::uint8_t>& bytes, T value) {
    std::uint8_t raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    bytes.insert(bytes.end(), raw, raw + sizeof(T));
}

// One triangle (0,0,0) (1,0,0) (0,1,0): 36 bytes of float positions, then
// three 32-bit indices at byte 36. Accessor 0 is POSITION, accessor 1 the
// indices; `position_extra` / `index_extra` replace their count and add
// fields (", \"byteOffset\": 8"). `nodes` is the JSON array of nodes, whose
// node 0 is the scene's root.
struct TriangleFile {
    std::string position_fields = R"("count":3)";
    std::string index_fields = R"("count":3)";
    std::string nodes = R"([{"mesh":0}])";
    bool with_indices = true;
    std::string primitive_extra;  // more primitive members, each starting with ','
    std::string extra;            // more top-level members, each starting with ','
};

inline std::string triangle_gltf(const TriangleFile& file) {
    std::vector<std::uint8_t> buffer;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) append(buffer, v);
    for (std::uint32_t i : {0u, 1u, 2u}) append(buffer, i);
    const std::string indices = (file.with_indices ? R"(,"indices":1)" : "") + file.primitive_extra;
    return fmt::format(
        R"({{"asset":{{"version":"2.0"}},)"
        R"("buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}],)"
        R"("bufferViews":[{{"buffer":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":12}}],)"
        R"("accessors":[{{"bufferView":0,"componentType":5126,"type":"VEC3",{}}},)"
        R"({{"bufferView":1,"componentType":5125,"type":"SCALAR",{}}}],)"
        R"("meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}{}}}]}}],)"
        R"("nodes":{},"scenes":[{{"nodes":[0]}}],"scene":0{}}})",
        buffer.size(), base64(buffer), file.position_fields, file.index_fields, indices, file.nodes,
        file.extra);
}

// Nodes 0..levels-1 each list the next node twice; node `levels` holds the
// mesh. The mesh is instantiated 2^levels times in 2^(levels+1) - 1 visits.
inline std::string dag_nodes(int levels) {
    std::string nodes = "[";
    for (int i = 0; i < levels; ++i) nodes += fmt::format(R"({{"children":[{0},{0}]}},)", i + 1);
    return nodes + R"({"mesh":0}])";
}

// JSON whose asset.extras nests `depth` arrays.
inline std::string deep_json(int depth) {
    return R"({"asset":{"version":"2.0","extras":)" + std::string(std::size_t(depth), '[') +
           std::string(std::size_t(depth), ']') + "}}";
}

// The start of a PNG file: signature and an IHDR chunk for an 8-bit RGBA
// image of the given size, with a correct CRC. Enough for any decoder to
// learn the size; the pixel data is absent.
inline std::vector<std::uint8_t> png_header(std::uint32_t width, std::uint32_t height) {
    std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    auto be32 = [](std::vector<std::uint8_t>& out, std::uint32_t v) {
        for (int shift = 24; shift >= 0; shift -= 8) out.push_back(std::uint8_t(v >> shift));
    };
    std::vector<std::uint8_t> chunk = {'I', 'H', 'D', 'R'};
    be32(chunk, width);
    be32(chunk, height);
    for (std::uint8_t v : {8, 6, 0, 0, 0}) chunk.push_back(v);
    std::uint32_t crc = 0xffffffffu;
    for (std::uint8_t byte : chunk) {
        crc ^= byte;
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    be32(png, 13);
    png.insert(png.end(), chunk.begin(), chunk.end());
    be32(png, crc ^ 0xffffffffu);
    return png;
}

// `TriangleFile::extra` members adding textures: one image per entry of
// `pngs`, each as a data URI, with material 0 using image 0.
inline std::string image_members(const std::vector<std::vector<std::uint8_t>>& pngs) {
    std::string images;
    std::string textures;
    for (std::size_t i = 0; i < pngs.size(); ++i) {
        images +=
            fmt::format(R"({}{{"uri":"data:image/png;base64,{}"}})", i ? "," : "", base64(pngs[i]));
        textures += fmt::format(R"({}{{"source":{}}})", i ? "," : "", i);
    }
    return fmt::format(
        R"(,"images":[{}],"textures":[{}],)"
        R"("materials":[{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}}}}}}])",
        images, textures);
}

// A GLB container: the JSON chunk (padded with spaces) and the binary chunk
// (padded with zeros), lengths as the specification lays them out.
inline std::string glb(const std::string& json, const std::vector<std::uint8_t>& binary) {
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

// The triangle as a GLB whose material's texture is `png`, stored in buffer
// view 2 right after the triangle's 48 bytes. `view_offset` and
// `view_length` (-1: the PNG's) set that view's fields, so a test can point it
// past the buffer; `buffer_length` (-1: all the bytes) sets the buffer's.
inline std::string textured_glb(const std::vector<std::uint8_t>& png, std::int64_t view_offset = 48,
                                std::int64_t view_length = -1, std::int64_t buffer_length = -1) {
    std::vector<std::uint8_t> bin;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) append(bin, v);
    for (std::uint32_t i : {0u, 1u, 2u}) append(bin, i);
    bin.insert(bin.end(), png.begin(), png.end());
    const std::string json = fmt::format(
        R"({{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":{}}}],)"
        R"("bufferViews":[{{"buffer":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":12}},)"
        R"({{"buffer":0,"byteOffset":{},"byteLength":{}}}],)"
        R"("accessors":[{{"bufferView":0,"componentType":5126,"type":"VEC3","count":3}},)"
        R"({{"bufferView":1,"componentType":5125,"type":"SCALAR","count":3}}],)"
        R"("meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1,"material":0}}]}}],)"
        R"("nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0,)"
        R"("images":[{{"bufferView":2,"mimeType":"image/png"}}],"textures":[{{"source":0}}],)"
        R"("materials":[{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}}}}}}]}})",
        buffer_length >= 0 ? std::uint64_t(buffer_length) : bin.size(), view_offset,
        view_length >= 0 ? std::uint64_t(view_length) : png.size());
    return glb(json, bin);
}

// Nodes fanning out `fan` by `fan`: the root lists nodes 1..fan, each of
// which lists all of nodes fan+1..2 fan, each holding the triangle's mesh.
// fan^2 instances in 1 + fan + fan^2 visits, from O(fan^2) bytes of JSON.
inline std::string fan_out_nodes(int fan) {
    std::string layer;
    for (int i = 0; i < fan; ++i) layer += fmt::format("{}{}", i ? "," : "", fan + 1 + i);
    std::string nodes = "[{\"children\":[";
    for (int i = 0; i < fan; ++i) nodes += fmt::format("{}{}", i ? "," : "", 1 + i);
    nodes += "]}";
    for (int i = 0; i < fan; ++i) nodes += ",{\"children\":[" + layer + "]}";
    for (int i = 0; i < fan; ++i) nodes += R"(,{"mesh":0})";
    return nodes + "]";
}

}  // namespace deepgi::test
