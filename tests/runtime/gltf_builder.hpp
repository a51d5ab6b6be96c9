#pragma once
// A small writer of glTF 2.0 JSON for render tests: every accessor, mesh,
// node and material is added from plain numbers, so where each surface lies
// and what colour it has follows from the test's own construction.
#include "../support/gltf_support.hpp"

#include <fmt/format.h>

#include <array>
#include <string>
#include <vector>

namespace deepgi::test {

class GltfBuilder {
public:
    // Appends `values` (each of `component_bytes` bytes) as one accessor.
    template <typename T>
    int accessor(const std::vector<T>& values, int component_type, const std::string& type,
                 int count, bool normalized = false) {
        while (buffer_.size() % 4 != 0) buffer_.push_back(0);
        const std::size_t offset = buffer_.size();
        for (T v : values) append(buffer_, v);
        views_.push_back(fmt::format(R"({{"buffer":0,"byteOffset":{},"byteLength":{}}})", offset,
                                     values.size() * sizeof(T)));
        accessors_.push_back(fmt::format(
            R"({{"bufferView":{},"componentType":{},"type":"{}","count":{}{}}})", views_.size() - 1,
            component_type, type, count, normalized ? R"(,"normalized":true)" : ""));
        return int(accessors_.size()) - 1;
    }
    int vec3s(const std::vector<std::array<float, 3>>& points) {
        std::vector<float> flat;
        for (const auto& p : points) flat.insert(flat.end(), p.begin(), p.end());
        return accessor(flat, 5126, "VEC3", int(points.size()));
    }
    int vec2s(const std::vector<std::array<float, 2>>& points) {
        std::vector<float> flat;
        for (const auto& p : points) flat.insert(flat.end(), p.begin(), p.end());
        return accessor(flat, 5126, "VEC2", int(points.size()));
    }

    // `primitives` is the JSON array's contents; returns the node's index,
    // which becomes a root of the scene.
    int mesh_node(const std::string& primitives, const std::string& node_fields = "") {
        meshes_.push_back(fmt::format(R"({{"primitives":[{}]}})", primitives));
        return node(fmt::format(R"("mesh":{}{})", meshes_.size() - 1, node_fields));
    }
    int node(const std::string& fields) {
        nodes_.push_back("{" + fields + "}");
        return int(nodes_.size()) - 1;
    }
    int material(const std::string& json) { return push(materials_, json); }
    int camera(const std::string& json) { return push(cameras_, json); }
    int light(const std::string& json) { return push(lights_, json); }
    int sampler(const std::string& json) { return push(samplers_, json); }
    // An embedded PNG and a texture reading it through `sampler` (-1: none).
    int texture(const std::vector<std::uint8_t>& png, int sampler_index = -1) {
        images_.push_back(fmt::format(R"({{"uri":"data:image/png;base64,{}"}})", base64(png)));
        return push(textures_,
                    fmt::format(R"({{"source":{}{}}})", images_.size() - 1,
                                sampler_index >= 0 ? fmt::format(R"(,"sampler":{})", sampler_index)
                                                   : std::string()));
    }
    void use_extension(const std::string& name) { extensions_.push_back(name); }

    // A quad facing +Z (counter-clockwise seen from +Z), centre (x, y, z),
    // side `size`, with UV (0,0) at the lower left and (1,1) at the upper
    // right. `mode` 4 (triangles, indexed), 5 (strip) or 6 (fan).
    // `uv_scale` multiplies the texture coordinates (2: the texture twice across).
    std::string quad(float x, float y, float z, float size, int material_index, int mode = 4,
                     const std::string& extra_attributes = "", float uv_scale = 1.0f) {
        const float h = size / 2;
        // Lower left, lower right, upper right, upper left.
        std::vector<std::array<float, 3>> corners = {
            {x - h, y - h, z}, {x + h, y - h, z}, {x + h, y + h, z}, {x - h, y + h, z}};
        const float k = uv_scale;
        std::vector<std::array<float, 2>> uvs = {{0, k}, {k, k}, {k, 0}, {0, 0}};
        std::string indices;
        if (mode == 5) {  // strip: LL LR UL UR
            std::swap(corners[2], corners[3]);
            std::swap(uvs[2], uvs[3]);
        } else if (mode == 4) {
            indices = fmt::format(
                R"(,"indices":{})",
                accessor(std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3}, 5123, "SCALAR", 6));
        }
        const int position = vec3s(corners);
        const int normal = vec3s({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
        const int uv = vec2s(uvs);
        return fmt::format(
            R"({{"attributes":{{"POSITION":{},"NORMAL":{},"TEXCOORD_0":{}{}}},"mode":{},"material":{}{}}})",
            position, normal, uv, extra_attributes, mode, material_index, indices);
    }

    std::string json() const {
        std::string roots;
        for (std::size_t i = 0; i < nodes_.size(); ++i)
            roots += fmt::format("{}{}", i ? "," : "", i);
        std::string text = R"({"asset":{"version":"2.0"})";
        if (!buffer_.empty())
            text += fmt::format(
                R"(,"buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}])",
                buffer_.size(), base64(buffer_));
        auto list = [&](const char* name, const std::vector<std::string>& items) {
            if (items.empty()) return;
            text += fmt::format(R"(,"{}":[)", name);
            for (std::size_t i = 0; i < items.size(); ++i) text += (i ? "," : "") + items[i];
            text += "]";
        };
        list("bufferViews", views_);
        list("accessors", accessors_);
        list("meshes", meshes_);
        list("materials", materials_);
        list("cameras", cameras_);
        list("samplers", samplers_);
        list("images", images_);
        list("textures", textures_);
        list("nodes", nodes_);
        std::vector<std::string> quoted;
        for (const auto& e : extensions_) quoted.push_back("\"" + e + "\"");
        list("extensionsUsed", quoted);
        if (!lights_.empty()) {
            text += R"(,"extensions":{"KHR_lights_punctual":{"lights":[)";
            for (std::size_t i = 0; i < lights_.size(); ++i) text += (i ? "," : "") + lights_[i];
            text += "]}}";
        }
        text += fmt::format(R"(,"scenes":[{{"nodes":[{}]}}],"scene":0}})", roots);
        return text;
    }

private:
    static int push(std::vector<std::string>& list, const std::string& json) {
        list.push_back(json);
        return int(list.size()) - 1;
    }
    std::vector<std::uint8_t> buffer_;
    std::vector<std::string> views_, accessors_, meshes_, materials_, cameras_, lights_, samplers_,
        images_, textures_, nodes_, extensions_;
};

}  // namespace deepgi::test
