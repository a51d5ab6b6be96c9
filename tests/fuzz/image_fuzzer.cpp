// libFuzzer target: image decoding through the glTF loader. The input's
// first byte chooses how the image's buffer view is laid out (exact, one
// byte past the buffer, starting past it, or a length near 2^31 / 2^32); the
// rest is the image file (PNG, JPEG, anything stb might be handed), stored in
// buffer view 2 of a GLB around a textured triangle. This drives the view
// checks, the size checks from the image header, the decoder and the RGBA8
// conversion, which the JSON fuzzer rarely reaches with a decodable image.
#include "deepgi/errors.hpp"
#include "deepgi/scene.hpp"

#include <fmt/format.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

namespace {

void append_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int shift = 0; shift < 32; shift += 8) out.push_back(std::uint8_t(v >> shift));
}

std::vector<std::uint8_t> textured_glb(std::span<const std::uint8_t> image, std::uint8_t layout) {
    std::vector<std::uint8_t> bin;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) {
        std::uint32_t bits = 0;
        std::memcpy(&bits, &v, 4);
        append_u32(bin, bits);
    }
    for (std::uint32_t i : {0u, 1u, 2u}) append_u32(bin, i);
    bin.insert(bin.end(), image.begin(), image.end());
    const std::uint64_t buffer_length = bin.size();
    while (bin.size() % 4) bin.push_back(0);
    std::uint64_t offset = 48;
    std::uint64_t length = image.size();
    switch (layout % 6) {
        case 1:
            length += 1;
            break;
        case 2:
            offset = buffer_length + 4;
            break;
        case 3:
            length = 0x7fffffffu;
            break;
        case 4:
            length = 0x100000000ull + image.size();
            break;
        case 5:
            length = image.size() / 2;
            break;
        default:
            break;
    }
    std::string json = fmt::format(
        R"({{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":{}}}],)"
        R"("bufferViews":[{{"buffer":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":12}},)"
        R"({{"buffer":0,"byteOffset":{},"byteLength":{}}}],)"
        R"("accessors":[{{"bufferView":0,"componentType":5126,"type":"VEC3","count":3}},)"
        R"({{"bufferView":1,"componentType":5125,"type":"SCALAR","count":3}}],)"
        R"("meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1,"material":0}}]}}],)"
        R"("nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0,)"
        R"("images":[{{"bufferView":2,"mimeType":"image/png"}}],"textures":[{{"source":0}}],)"
        R"("materials":[{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}}}}}}]}})",
        buffer_length, offset, length);
    while (json.size() % 4) json += ' ';
    std::vector<std::uint8_t> out;
    const std::uint32_t total = std::uint32_t(12 + 8 + json.size() + 8 + bin.size());
    for (std::uint32_t v : {0x46546c67u, 2u, total, std::uint32_t(json.size()), 0x4e4f534au})
        append_u32(out, v);
    out.insert(out.end(), json.begin(), json.end());
    append_u32(out, std::uint32_t(bin.size()));
    append_u32(out, 0x004e4942u);
    out.insert(out.end(), bin.begin(), bin.end());
    return out;
}

}  // namespace

// Loads one input as the fuzzer does; true when the loader accepted it.
bool image_fuzz_load(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return false;
    deepgi::SceneLimits limits;
    limits.texture_side = 1024;
    limits.texture_bytes = 16u << 20;
    const std::vector<std::uint8_t> file = textured_glb({data + 1, size - 1}, data[0]);
    try {
        const deepgi::Scene scene =
            deepgi::load_gltf_scene_from_memory(file, true, "fuzz-image", limits);
        // A texture that loads is whole: width x height RGBA8 texels.
        for (const auto& texture : scene.textures)
            if (texture.width < 1 || texture.height < 1 ||
                texture.rgba8.size() !=
                    std::size_t(texture.width) * std::size_t(texture.height) * 4)
                __builtin_trap();
        // A view that leaves the buffer (layouts 1 to 4) must be refused. The
        // halved view (layout 5) may load: its first half can be a whole
        // image, as when the input is one image file twice over.
        const int layout = data[0] % 6;
        if (layout != 0 && layout != 5) __builtin_trap();
        return true;
    } catch (const deepgi::InputError&) {
        return false;
    }
}

// For the corpus replay (replay_main.cpp).
bool fuzz_target_accepts(const std::uint8_t* data, std::size_t size) {
    return image_fuzz_load(data, size);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    image_fuzz_load(data, size);
    return 0;
}
