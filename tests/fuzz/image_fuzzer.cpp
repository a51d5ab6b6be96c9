// libFuzzer target: image decoding through the glTF loader. The input's
// first byte chooses how the image's buffer view is laid out (exact, one
// byte past the buffer, starting past it, or a length near 2^31 / 2^32); the
// rest is the image file (PNG, JPEG, anything stb might be handed), stored in
// buffer view 2 of a GLB around a textured triangle. This drives the view
// checks, the size checks from the image header, the decoder and the RGBA8
// conversion, which the JSON fuzzer rarely reaches with a decodable image.
#include "deepgi/errors.hpp"
#include "deepgi/scene.hpp"
#include "gltf_support.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace {

// The textured triangle's GLB (gltf_support.hpp) with its image view laid
// out as `layout` says.
std::vector<std::uint8_t> textured_glb(std::span<const std::uint8_t> image, std::uint8_t layout) {
    const auto size = std::int64_t(image.size());
    const std::int64_t buffer_length = 48 + size;
    std::int64_t offset = 48;
    std::int64_t length = size;
    switch (layout % 6) {
        case 1:
            length += 1;
            break;
        case 2:
            offset = buffer_length + 4;
            break;
        case 3:
            length = 0x7fffffff;
            break;
        case 4:
            length = 0x100000000ll + size;
            break;
        case 5:
            length = size / 2;
            break;
        default:
            break;
    }
    const std::string file =
        deepgi::test::textured_glb({image.begin(), image.end()}, offset, length);
    return {file.begin(), file.end()};
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
