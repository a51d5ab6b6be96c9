// The glTF loader's parts, shared between its files: the checked reader and
// limits (gltf_reader.cpp), images (gltf_images.cpp), scene assembly
// (gltf_scene_build.cpp) and loading (scene_gltf.cpp). Internal to deepgi_scene.
#pragma once

#include "deepgi/errors.hpp"
#include "deepgi/scene.hpp"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

namespace deepgi::gltf {

// A message from a library, on one line.
std::string one_line(std::string text);

// Every offset, stride and count in a glTF file is attacker-controlled and
// 64 bits wide; a plain `a + b * c` wraps and turns a bounds check into a
// wild read. All such arithmetic goes through these, which fail naming the
// accessor instead of wrapping.
struct CheckedSize {
    std::function<void(const std::string&)> fail;  // throws
    std::string_view subject;                      // "accessor 3"

    std::size_t add(std::size_t a, std::size_t b, std::string_view what) const {
        std::size_t result = 0;
        if (__builtin_add_overflow(a, b, &result)) overflow(what);
        return result;
    }
    std::size_t mul(std::size_t a, std::size_t b, std::string_view what) const {
        std::size_t result = 0;
        if (__builtin_mul_overflow(a, b, &result)) overflow(what);
        return result;
    }
    [[noreturn]] void overflow(std::string_view what) const {
        fail(fmt::format("{}: {} overflows 64 bits", subject, what));
        std::abort();  // fail throws; this only tells the compiler
    }
};

class GltfReader {
public:
    GltfReader(const tinygltf::Model& model, std::string name)
        : model_(model), name_(std::move(name)) {}

    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(fmt::format("glTF file '{}': {}", name_, what));
    }

    // Returns component `c` of element `i` as float, honouring byteStride and
    // normalised integer types; every offset is bounds checked.
    // `raw`, when given, receives the first element's address and the stride
    // (for integer reads that must not pass through float).
    std::function<float(std::size_t, int)> accessor_reader(
        int accessor_index, int expected_components, std::size_t& count,
        std::pair<const std::uint8_t*, std::size_t>* raw = nullptr) const;

    std::vector<std::uint32_t> read_indices(int accessor_index) const;

    const tinygltf::Model& model_;
    std::string name_;
};

// Deepest nesting of JSON arrays and objects in `text`, stopping early once
// past `limit`.
std::uint64_t json_depth(std::string_view text, std::uint64_t limit);

// The JSON text of a .gltf file, or the JSON chunk of a .glb file.
std::string_view json_text(std::span<const std::uint8_t> bytes, bool binary);

// The first external URI in the JSON text (a "uri" member that is not a
// data: URI) whose percent-escapes are malformed or decode to NUL, described;
// "" when there is none. tinygltf decodes "%zz" to a NUL byte and keeps a
// trailing "%" as it is, so a URI must be checked before it names a file.
std::string malformed_uri(std::string_view json);

enum class GltfKind { none, json, binary };

// What the bytes are, by content (not by the file's name).
GltfKind sniff_gltf(std::span<const std::uint8_t> bytes);

// The value of --scene-limit NAME=VALUE: a whole number >= 1.
std::uint64_t parse_limit_value(std::string_view name, std::string_view text);

// tinygltf's image callback: checks each image's size from its header before
// decoding, against the texture limits. `user_data` is an ImageBudget.
// `model` is the model being parsed: its buffers and views are complete when
// the images are read, and an image stored in a view is checked against them.
struct ImageBudget {
    const SceneLimits* limits = nullptr;
    const tinygltf::Model* model = nullptr;
    std::uint64_t decoded_bytes = 0;
};
bool load_image_within_limits(tinygltf::Image* image, int image_index, std::string* error,
                              std::string* warning, int, int, const unsigned char* bytes, int size,
                              void* user_data);

// A decoded image as RGBA8.
TextureImage convert_image(const tinygltf::Image& image, const GltfReader& reader);

// A glTF sampler as GL enums.
TextureSampler read_sampler(const tinygltf::Sampler& source, int index, const GltfReader& reader);

// The renderer's scene from a parsed model: flattens the node graph within
// the limits, converts materials, textures, cameras and the key light.
Scene build_scene(const tinygltf::Model& model, const std::string& display_name,
                  const std::string& scene_name, const SceneLimits& limits);

}  // namespace deepgi::gltf
