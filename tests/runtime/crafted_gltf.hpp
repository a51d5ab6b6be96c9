// What the two test files of the glTF loader share (scene_gltf_geometry_test.cpp,
// scene_gltf_materials_test.cpp): loading a file crafted in the test from
// memory, the loader's message when it refuses one, a PNG encoded in memory,
// and a five-vertex file drawn by primitives of any mode. The render tests
// (rendered_gltf.hpp) load their files and encode their textures with it too.
#pragma once

#include "deepgi/errors.hpp"
#include "deepgi/scene.hpp"
#include "../support/gltf_support.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <stb_image_write.h>

#include <cstdint>
#include <string>
#include <vector>

namespace deepgi::test {

inline deepgi::Scene load(const std::string& json, const deepgi::SceneLimits& limits = {}) {
    return deepgi::load_gltf_scene_from_memory(
        {reinterpret_cast<const std::uint8_t*>(json.data()), json.size()}, false, "crafted.gltf",
        limits);
}

// The loader's message for `json`, or "" when it loads.
inline std::string refusal(const std::string& json, const deepgi::SceneLimits& limits = {}) {
    try {
        load(json, limits);
    } catch (const deepgi::InputError& error) {
        return error.what();
    }
    return "";
}

inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

inline std::vector<std::uint8_t> encode_png(int width, int height,
                                            const std::vector<std::uint8_t>& rgba) {
    std::vector<std::uint8_t> png;
    auto sink = [](void* context, void* data, int size) {
        auto& out = *static_cast<std::vector<std::uint8_t>*>(context);
        out.insert(out.end(), static_cast<std::uint8_t*>(data),
                   static_cast<std::uint8_t*>(data) + size);
    };
    REQUIRE(stbi_write_png_to_func(sink, &png, width, height, 4, rgba.data(), width * 4) != 0);
    return png;
}

// Five vertices v0 (0,0,0), v1 (1,0,0), v2 (0,1,0), v3 (1,1,0), v4 (0,2,0),
// unindexed, drawn by one primitive per entry of `modes`.
inline std::string five_vertex_gltf(const std::vector<int>& modes) {
    std::vector<std::uint8_t> buffer;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f, 0.f, 2.f, 0.f})
        append(buffer, v);
    std::string primitives;
    for (int mode : modes)
        primitives += fmt::format(R"({}{{"attributes":{{"POSITION":0}},"mode":{}}})",
                                  primitives.empty() ? "" : ",", mode);
    return fmt::format(
        R"({{"asset":{{"version":"2.0"}},)"
        R"("buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}],)"
        R"("bufferViews":[{{"buffer":0,"byteLength":{}}}],)"
        R"("accessors":[{{"bufferView":0,"componentType":5126,"type":"VEC3","count":5}}],)"
        R"("meshes":[{{"primitives":[{}]}}],"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}]}})",
        buffer.size(), base64(buffer), buffer.size(), primitives);
}

}  // namespace deepgi::test
