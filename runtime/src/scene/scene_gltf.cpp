// glTF 2.0 through tinygltf. Reads positions, normals, TEXCOORD_0 (to look up
// the textures), COLOR_0, base colour factor and texture with its sampler,
// alpha mode and cutoff, emissive factor, texture and strength, cameras and
// KHR_lights_punctual; everything else is named in one summary warning.
#include "deepgi/errors.hpp"
#include "deepgi/scene.hpp"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <stb_image.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <map>

namespace deepgi {

namespace fs = std::filesystem;

namespace {

std::string one_line(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    std::replace(text.begin(), text.end(), '\r', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

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
        std::pair<const std::uint8_t*, std::size_t>* raw = nullptr) const {
        if (accessor_index < 0 || accessor_index >= int(model_.accessors.size()))
            fail("accessor index out of range");
        const auto& accessor = model_.accessors[std::size_t(accessor_index)];
        const int components =
            tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
        if (components != expected_components)
            fail(fmt::format("accessor {} has {} components, expected {}", accessor_index,
                             components, expected_components));
        if (accessor.bufferView < 0 || accessor.bufferView >= int(model_.bufferViews.size()))
            fail(fmt::format("accessor {} has no valid buffer view", accessor_index));
        const auto& view = model_.bufferViews[std::size_t(accessor.bufferView)];
        if (view.buffer < 0 || view.buffer >= int(model_.buffers.size()))
            fail("buffer view refers to a missing buffer");
        const auto& buffer = model_.buffers[std::size_t(view.buffer)];
        const int component_size =
            tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor.componentType));
        if (component_size <= 0)
            fail(fmt::format("accessor {} has an unknown component type", accessor_index));
        const std::string subject = fmt::format("accessor {}", accessor_index);
        const CheckedSize checked{[this](const std::string& what) { fail(what); }, subject};
        const std::size_t element_size = std::size_t(component_size * components);
        const std::size_t stride = view.byteStride != 0 ? view.byteStride : element_size;
        if (stride < element_size)
            fail(fmt::format("{}: byteStride {} is smaller than one element ({} bytes)", subject,
                             stride, element_size));
        count = accessor.count;
        // The view must lie inside its buffer, and every element inside the view.
        const std::size_t view_end =
            checked.add(view.byteOffset, view.byteLength, "bufferView byteOffset + byteLength");
        if (view_end > buffer.data.size())
            fail(fmt::format("{}: its buffer view ends at byte {}, past the buffer's {} bytes",
                             subject, view_end, buffer.data.size()));
        const std::size_t begin =
            checked.add(view.byteOffset, accessor.byteOffset, "bufferView + accessor byteOffset");
        if (begin > view_end)
            fail(fmt::format("{}: starts at byte {}, past the end of its buffer view at byte {}",
                             subject, begin, view_end));
        if (count > 0) {
            const std::size_t span =
                checked.add(checked.mul(count - 1, stride, "count x byteStride"), element_size,
                            "count x byteStride + element size");
            const std::size_t end = checked.add(begin, span, "byteOffset + count x byteStride");
            if (end > view_end)
                fail(
                    fmt::format("{}: {} elements from byte {} end at byte {}, past the end of "
                                "its buffer view at byte {}",
                                subject, count, begin, end, view_end));
        }
        const std::uint8_t* data = buffer.data.data() + begin;
        if (raw) *raw = {data, stride};
        const int type = accessor.componentType;
        const bool normalized = accessor.normalized;
        return [=](std::size_t i, int c) -> float {
            const std::uint8_t* p = data + i * stride + std::size_t(c * component_size);
            switch (type) {
                case TINYGLTF_COMPONENT_TYPE_FLOAT: {
                    float v;
                    std::memcpy(&v, p, 4);
                    return v;
                }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                    return normalized ? float(*p) / 255.0f : float(*p);
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                    std::uint16_t v;
                    std::memcpy(&v, p, 2);
                    return normalized ? float(v) / 65535.0f : float(v);
                }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
                    std::uint32_t v;
                    std::memcpy(&v, p, 4);
                    return float(v);
                }
                case TINYGLTF_COMPONENT_TYPE_BYTE: {
                    std::int8_t v;
                    std::memcpy(&v, p, 1);
                    return normalized ? std::max(float(v) / 127.0f, -1.0f) : float(v);
                }
                case TINYGLTF_COMPONENT_TYPE_SHORT: {
                    std::int16_t v;
                    std::memcpy(&v, p, 2);
                    return normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
                }
                default:
                    return 0.0f;
            }
        };
    }

    std::vector<std::uint32_t> read_indices(int accessor_index) const {
        const auto& accessor = model_.accessors.at(std::size_t(accessor_index));
        if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            fail("indices must be unsigned integers");
        }
        std::size_t count = 0;
        std::pair<const std::uint8_t*, std::size_t> raw;
        accessor_reader(accessor_index, 1, count, &raw);
        // Read as integers: through float, 32-bit indices above 2^24 lose
        // bits and 0xffffffff rounds to 2^32, which no uint32 holds.
        const auto [data, stride] = raw;
        std::vector<std::uint32_t> indices(count);
        for (std::size_t i = 0; i < count; ++i) {
            const std::uint8_t* p = data + i * stride;
            if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
                indices[i] = *p;
            } else if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
                std::uint16_t v;
                std::memcpy(&v, p, 2);
                indices[i] = v;
            } else {
                std::memcpy(&indices[i], p, 4);
            }
        }
        return indices;
    }

    const tinygltf::Model& model_;
    std::string name_;
};

glm::mat4 node_transform(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        glm::mat4 matrix;
        for (int i = 0; i < 16; ++i) glm::value_ptr(matrix)[i] = float(node.matrix[std::size_t(i)]);
        return matrix;
    }
    glm::mat4 transform(1.0f);
    if (node.translation.size() == 3) {
        transform = glm::translate(
            transform, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
    }
    if (node.rotation.size() == 4) {
        glm::quat rotation(float(node.rotation[3]), float(node.rotation[0]),
                           float(node.rotation[1]), float(node.rotation[2]));
        transform *= glm::mat4_cast(rotation);
    }
    if (node.scale.size() == 3)
        transform = glm::scale(transform, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
    return transform;
}

TextureImage convert_image(const tinygltf::Image& image, const GltfReader& reader) {
    if (image.bits != 8 || image.width <= 0 || image.height <= 0 || image.component < 1 ||
        image.component > 4) {
        reader.fail(fmt::format(
            "image '{}' is not an 8-bit image (only 8-bit textures are supported)", image.uri));
    }
    TextureImage texture;
    texture.width = image.width;
    texture.height = image.height;
    // The image loader already bounded width and height (texture-side), so
    // these products fit easily in 64 bits.
    const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
    if (image.image.size() / std::size_t(image.component) < pixels)
        reader.fail("image data is truncated");
    texture.rgba8.resize(pixels * 4);
    for (std::size_t i = 0; i < pixels; ++i) {
        const std::uint8_t* source = image.image.data() + i * std::size_t(image.component);
        std::uint8_t* target = texture.rgba8.data() + i * 4;
        // Grey, grey + alpha, RGB or RGBA; alpha feeds the alpha mask.
        if (image.component <= 2) {
            target[0] = target[1] = target[2] = source[0];
        } else {
            target[0] = source[0];
            target[1] = source[1];
            target[2] = source[2];
        }
        target[3] = image.component == 2 ? source[1] : image.component == 4 ? source[3] : 255;
    }
    return texture;
}

// A glTF sampler as GL enums; an absent filter (-1) gets the renderer's
// default (trilinear minification, linear magnification).
TextureSampler read_sampler(const tinygltf::Sampler& source, int index, const GltfReader& reader) {
    TextureSampler sampler;
    auto check = [&](int value, std::initializer_list<int> allowed, const char* field) {
        if (std::find(allowed.begin(), allowed.end(), value) == allowed.end())
            reader.fail(fmt::format("sampler {}: {} {} is not a valid value", index, field, value));
        return value;
    };
    if (source.magFilter != -1)
        sampler.mag_filter =
            check(source.magFilter,
                  {TINYGLTF_TEXTURE_FILTER_NEAREST, TINYGLTF_TEXTURE_FILTER_LINEAR}, "magFilter");
    if (source.minFilter != -1)
        sampler.min_filter = check(source.minFilter,
                                   {TINYGLTF_TEXTURE_FILTER_NEAREST, TINYGLTF_TEXTURE_FILTER_LINEAR,
                                    TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST,
                                    TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST,
                                    TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR,
                                    TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR},
                                   "minFilter");
    const std::initializer_list<int> wraps = {TINYGLTF_TEXTURE_WRAP_REPEAT,
                                              TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE,
                                              TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT};
    sampler.wrap_s = check(source.wrapS, wraps, "wrapS");
    sampler.wrap_t = check(source.wrapT, wraps, "wrapT");
    return sampler;
}

// Deepest nesting of JSON arrays and objects in `text`, stopping early once
// past `limit`; strings (with their escapes) are skipped. nlohmann::json and
// tinygltf's conversion recurse once per level, so a 40 KB file of brackets
// overflows the stack unless this runs first.
std::uint64_t json_depth(std::string_view text, std::uint64_t limit) {
    std::uint64_t depth = 0;
    std::uint64_t deepest = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '{' || c == '[') {
            deepest = std::max(deepest, ++depth);
            if (deepest > limit) break;
        } else if ((c == '}' || c == ']') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

std::uint32_t read_u32_le(const std::uint8_t* p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
           std::uint32_t(p[3]) << 24;
}

// The JSON text of a .gltf file, or the JSON chunk of a .glb file. A GLB
// whose header does not parse is scanned whole (tinygltf rejects it anyway).
std::string_view json_text(std::span<const std::uint8_t> bytes, bool binary) {
    const std::string_view all(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (!binary || bytes.size() < 20) return all;
    const std::size_t chunk_length = read_u32_le(bytes.data() + 12);
    return all.substr(20, std::min(chunk_length, bytes.size() - 20));
}

// tinygltf decodes every image while it parses; this decoder checks each
// image's size from its header first, so a 300 KB PNG cannot ask for
// gigabytes. Images always come out as 8 bits per channel.
struct ImageBudget {
    const SceneLimits* limits = nullptr;
    std::uint64_t decoded_bytes = 0;
};

bool load_image_within_limits(tinygltf::Image* image, const int image_index, std::string* error,
                              std::string*, int, int, const unsigned char* bytes, int size,
                              void* user_data) {
    auto& budget = *static_cast<ImageBudget*>(user_data);
    const SceneLimits& limits = *budget.limits;
    int width = 0;
    int height = 0;
    int components = 0;
    if (stbi_info_from_memory(bytes, size, &width, &height, &components) == 0 || width < 1 ||
        height < 1) {
        if (error) *error += fmt::format("image {} cannot be decoded. ", image_index);
        return false;
    }
    if (std::uint64_t(width) > limits.texture_side || std::uint64_t(height) > limits.texture_side) {
        if (error)
            *error += fmt::format(
                "image {} is {}x{} pixels, above the limit of {} per side (raise with "
                "--scene-limit texture-side=N). ",
                image_index, width, height, limits.texture_side);
        return false;
    }
    const std::uint64_t decoded = std::uint64_t(width) * std::uint64_t(height) * 4;
    if (decoded > limits.texture_bytes || budget.decoded_bytes > limits.texture_bytes - decoded) {
        if (error)
            *error += fmt::format(
                "image {} brings the decoded textures to {} bytes, above the limit of {} (raise "
                "with --scene-limit texture-bytes=N). ",
                image_index, budget.decoded_bytes + decoded, limits.texture_bytes);
        return false;
    }
    budget.decoded_bytes += decoded;
    int channels = 0;
    unsigned char* pixels =
        stbi_load_from_memory(bytes, size, &width, &height, &channels, STBI_rgb_alpha);
    if (pixels == nullptr) {
        if (error) *error += fmt::format("image {} cannot be decoded. ", image_index);
        return false;
    }
    image->width = width;
    image->height = height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image.assign(pixels, pixels + std::size_t(decoded));
    stbi_image_free(pixels);
    return true;
}

// For bytes loaded from memory: no URI may reach the file system.
bool no_file_exists(const std::string&, void*) {
    return false;
}
std::string no_expand(const std::string& path, void*) {
    return path;
}
bool no_read(std::vector<unsigned char>*, std::string* error, const std::string& path, void*) {
    if (error) *error += fmt::format("'{}' is external; only embedded data is accepted. ", path);
    return false;
}
bool no_write(std::string* error, const std::string&, const std::vector<unsigned char>&, void*) {
    if (error) *error += "writing is not supported. ";
    return false;
}

// Strips and fans as a plain triangle list, winding as the glTF specification
// defines it: strip triangle i is (i, i+1, i+2) for even i and (i, i+2, i+1)
// for odd i, so every triangle keeps the first one's orientation; fan triangle
// i is (i+1, i+2, 0).
std::vector<std::uint32_t> triangle_list(int mode, std::vector<std::uint32_t> indices) {
    if (mode == TINYGLTF_MODE_TRIANGLES) return indices;
    std::vector<std::uint32_t> triangles;
    const std::size_t n = indices.size();
    if (n < 3) return triangles;
    triangles.reserve((n - 2) * 3);
    for (std::size_t i = 0; i + 2 < n; ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            const bool odd = i % 2 == 1;
            triangles.insert(triangles.end(), {indices[i], indices[odd ? i + 2 : i + 1],
                                               indices[odd ? i + 1 : i + 2]});
        } else {
            triangles.insert(triangles.end(), {indices[i + 1], indices[i + 2], indices[0]});
        }
    }
    return triangles;
}

// "3 skins" / "1 skin"; empty for none.
std::string counted(std::uint64_t n, std::string_view noun) {
    if (n == 0) return "";
    return fmt::format("{} {}{}", n, noun, n == 1 ? "" : "s");
}

// One line naming everything in the file that the renderer does not use, so
// nothing is dropped silently: "ignored: 2 skins, 1 animation, KHR_texture_transform".
std::string ignored_summary(const tinygltf::Model& model, std::uint64_t orthographic_cameras) {
    std::uint64_t morph_targets = 0, extra_colour_sets = 0, tangents = 0, extra_uv_sets = 0;
    for (const auto& mesh : model.meshes) {
        for (const auto& primitive : mesh.primitives) {
            morph_targets += primitive.targets.size();
            for (const auto& [name, accessor] : primitive.attributes) {
                if (name.rfind("COLOR_", 0) == 0 && name != "COLOR_0") ++extra_colour_sets;
                if (name == "TANGENT") ++tangents;
                if (name.rfind("TEXCOORD_", 0) == 0 && name != "TEXCOORD_0") ++extra_uv_sets;
            }
        }
    }
    // Normal textures are skipped, not half-used: shading normals from a
    // normal map need tangents (given or MikkTSpace-generated), which the
    // G-buffer does not carry.
    std::uint64_t normal_maps = 0, occlusion_maps = 0, metal_rough_maps = 0;
    for (const auto& material : model.materials) {
        normal_maps += material.normalTexture.index >= 0;
        occlusion_maps += material.occlusionTexture.index >= 0;
        metal_rough_maps += material.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0;
    }
    std::vector<std::string> parts = {
        counted(model.skins.size(), "skin"),
        counted(model.animations.size(), "animation"),
        counted(morph_targets, "morph target"),
        counted(orthographic_cameras, "orthographic camera"),
        counted(extra_colour_sets, "extra vertex colour set"),
        counted(tangents, "tangent set"),
        counted(extra_uv_sets, "extra texture coordinate set"),
        counted(normal_maps, "normal texture"),
        counted(occlusion_maps, "occlusion texture"),
        counted(metal_rough_maps, "metallic-roughness texture"),
    };
    for (const auto& extension : model.extensionsUsed)
        if (extension != "KHR_materials_emissive_strength" && extension != "KHR_lights_punctual")
            parts.push_back(extension);
    std::string line;
    for (const auto& part : parts) {
        if (part.empty()) continue;
        line += line.empty() ? "ignored: " : ", ";
        line += part;
    }
    return line;
}

enum class GltfKind { none, json, binary };

// GLB starts with the magic "glTF"; a JSON glTF is an object, so its first
// non-blank byte (after an optional UTF-8 byte order mark) is '{'.
GltfKind sniff_gltf(std::span<const std::uint8_t> bytes) {
    if (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0) return GltfKind::binary;
    std::size_t i = 0;
    if (bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF) i = 3;
    while (i < bytes.size() &&
           (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\n' || bytes[i] == '\r'))
        ++i;
    return i < bytes.size() && bytes[i] == '{' ? GltfKind::json : GltfKind::none;
}

std::uint64_t parse_limit_value(std::string_view name, std::string_view text) {
    std::uint64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || value == 0)
        throw InputError(
            fmt::format("--scene-limit {}={}: the value must be a whole number >= 1", name, text));
    return value;
}

// The checked, limited parse into tinygltf's model. Returned by value so the
// caller can free the file's bytes before the scene is built (peak memory).
tinygltf::Model parse_gltf(std::span<const std::uint8_t> bytes, bool binary,
                           const std::string& display_name, const std::string& base_dir,
                           bool allow_files, const SceneLimits& limits) {
    const std::uint64_t depth = json_depth(json_text(bytes, binary), limits.json_depth);
    if (depth > limits.json_depth)
        throw InputError(fmt::format(
            "glTF file '{}': JSON nests deeper than {} levels (raise with --scene-limit "
            "json-depth=N)",
            display_name, limits.json_depth));
    // tinygltf takes the length as unsigned int.
    if (bytes.size() > 0xffffffffu)
        throw InputError(fmt::format("glTF file '{}' is larger than 4 GiB", display_name));
    tinygltf::TinyGLTF loader;
    ImageBudget budget{&limits, 0};
    loader.SetImageLoader(load_image_within_limits, &budget);
    if (!allow_files)
        loader.SetFsCallbacks(
            tinygltf::FsCallbacks{no_file_exists, no_expand, no_read, no_write, nullptr});
    tinygltf::Model model;
    std::string error;
    std::string warning;
    const bool loaded =
        binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(),
                                             unsigned(bytes.size()), base_dir)
               : loader.LoadASCIIFromString(&model, &error, &warning,
                                            reinterpret_cast<const char*>(bytes.data()),
                                            unsigned(bytes.size()), base_dir);
    if (!loaded) {
        throw InputError(fmt::format("cannot load glTF file '{}': {}", display_name,
                                     one_line(error.empty() ? "unknown error" : error)));
    }
    return model;
}

Scene build_scene(const tinygltf::Model& model, const std::string& display_name,
                  const std::string& scene_name, const SceneLimits& limits) {
    GltfReader reader(model, display_name);

    Scene scene;
    scene.name = scene_name;
    // Material -1 (none) becomes the glTF default material, appended last.
    std::map<int, std::vector<std::uint32_t>> indices_by_material;
    std::map<int, int> texture_of_image;
    std::uint64_t triangles = 0;

    std::uint64_t skipped_points_and_lines = 0;

    auto add_primitive = [&](const tinygltf::Primitive& primitive, const glm::mat4& transform) {
        const int mode = primitive.mode == -1 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
        if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE ||
            mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
            // Not surfaces: nothing for a G-buffer to hold. Counted for one warning.
            ++skipped_points_and_lines;
            return;
        }
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            reader.fail(fmt::format("primitive mode {} is not supported", primitive.mode));
        }
        const auto position_attribute = primitive.attributes.find("POSITION");
        if (position_attribute == primitive.attributes.end())
            reader.fail("a primitive has no POSITION attribute");
        std::size_t vertex_count = 0;
        auto read_position = reader.accessor_reader(position_attribute->second, 3, vertex_count);
        std::function<float(std::size_t, int)> read_normal;
        std::function<float(std::size_t, int)> read_uv;
        if (auto it = primitive.attributes.find("NORMAL"); it != primitive.attributes.end()) {
            std::size_t count = 0;
            read_normal = reader.accessor_reader(it->second, 3, count);
            if (count != vertex_count) reader.fail("NORMAL and POSITION counts differ");
        }
        if (auto it = primitive.attributes.find("TEXCOORD_0"); it != primitive.attributes.end()) {
            std::size_t count = 0;
            read_uv = reader.accessor_reader(it->second, 2, count);
            if (count != vertex_count) reader.fail("TEXCOORD_0 and POSITION counts differ");
        }
        // COLOR_0: RGB or RGBA, float or normalised unsigned byte or short
        // (the only forms the specification allows), linear.
        std::function<float(std::size_t, int)> read_colour;
        int colour_components = 0;
        if (auto it = primitive.attributes.find("COLOR_0"); it != primitive.attributes.end()) {
            if (it->second < 0 || it->second >= int(model.accessors.size()))
                reader.fail("accessor index out of range");
            const auto& accessor = model.accessors[std::size_t(it->second)];
            colour_components = accessor.type == TINYGLTF_TYPE_VEC3   ? 3
                                : accessor.type == TINYGLTF_TYPE_VEC4 ? 4
                                                                      : 0;
            const bool float_colour = accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
            const bool normalised_colour =
                accessor.normalized &&
                (accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                 accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
            if (colour_components == 0 || !(float_colour || normalised_colour))
                reader.fail(fmt::format(
                    "COLOR_0 (accessor {}) must be VEC3 or VEC4 of float, or of normalized "
                    "unsigned byte or short",
                    it->second));
            std::size_t count = 0;
            read_colour = reader.accessor_reader(it->second, colour_components, count);
            if (count != vertex_count) reader.fail("COLOR_0 and POSITION counts differ");
        }
        std::vector<std::uint32_t> local_indices;
        if (primitive.indices >= 0) {
            local_indices = reader.read_indices(primitive.indices);
        } else {
            local_indices.resize(vertex_count);
            for (std::size_t i = 0; i < vertex_count; ++i)
                local_indices[i] = static_cast<std::uint32_t>(i);
        }
        local_indices = triangle_list(mode, std::move(local_indices));
        if (local_indices.size() % 3 != 0)
            reader.fail("triangle index count is not a multiple of 3");
        if (primitive.material >= int(model.materials.size()))
            reader.fail("material index out of range");
        const bool double_sided =
            primitive.material >= 0 && model.materials[std::size_t(primitive.material)].doubleSided;
        // Counted before any vertex is emitted, so an instanced mesh stops here.
        triangles += (local_indices.size() / 3) * (double_sided ? 2 : 1);
        if (triangles > limits.triangles)
            reader.fail(fmt::format(
                "the scene instantiates more than {} triangles (raise with --scene-limit "
                "triangles=N)",
                limits.triangles));
        for (auto index : local_indices) {
            if (index >= vertex_count) reader.fail("an index refers past the end of the vertices");
        }
        const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(transform)));
        const bool mirrored = glm::determinant(glm::mat3(transform)) < 0.0f;
        // Without normals every triangle gets its own flat-shaded vertices.
        const bool flat = !read_normal;
        auto& target = indices_by_material[primitive.material];
        // The renderer culls back faces, so a double-sided material gets each
        // triangle twice: the back copy wound the other way, its normal flipped.
        auto emit_vertex = [&](std::uint32_t i, glm::vec3 flat_normal, bool back = false) {
            Vertex vertex;
            vertex.position =
                glm::vec3(transform * glm::vec4(read_position(i, 0), read_position(i, 1),
                                                read_position(i, 2), 1.0f));
            vertex.normal =
                flat
                    ? flat_normal
                    : glm::normalize(normal_matrix * glm::vec3(read_normal(i, 0), read_normal(i, 1),
                                                               read_normal(i, 2)));
            if (!std::isfinite(vertex.normal.x)) vertex.normal = flat_normal;
            if (back) vertex.normal = -vertex.normal;
            vertex.uv = read_uv ? glm::vec2(read_uv(i, 0), read_uv(i, 1)) : glm::vec2(0.0f);
            if (read_colour) {
                vertex.colour = glm::vec4(read_colour(i, 0), read_colour(i, 1), read_colour(i, 2),
                                          colour_components == 4 ? read_colour(i, 3) : 1.0f);
                if (!std::isfinite(vertex.colour.r + vertex.colour.g + vertex.colour.b +
                                   vertex.colour.a))
                    reader.fail("a COLOR_0 value is not finite");
            }
            if (!std::isfinite(vertex.position.x) || !std::isfinite(vertex.position.y) ||
                !std::isfinite(vertex.position.z)) {
                reader.fail("a vertex position is not finite");
            }
            scene.vertices.push_back(vertex);
            target.push_back(static_cast<std::uint32_t>(scene.vertices.size() - 1));
        };
        for (std::size_t t = 0; t < local_indices.size(); t += 3) {
            std::uint32_t a = local_indices[t];
            std::uint32_t b = local_indices[t + 1];
            std::uint32_t c = local_indices[t + 2];
            if (mirrored) std::swap(b, c);
            auto world = [&](std::uint32_t i) {
                return glm::vec3(transform * glm::vec4(read_position(i, 0), read_position(i, 1),
                                                       read_position(i, 2), 1.0f));
            };
            glm::vec3 face = glm::cross(world(b) - world(a), world(c) - world(a));
            const float length = glm::length(face);
            const glm::vec3 flat_normal = length > 0.0f ? face / length : glm::vec3(0, 1, 0);
            emit_vertex(a, flat_normal);
            emit_vertex(b, flat_normal);
            emit_vertex(c, flat_normal);
            if (double_sided) {
                emit_vertex(a, flat_normal, true);
                emit_vertex(c, flat_normal, true);
                emit_vertex(b, flat_normal, true);
            }
        }
    };

    // A glTF camera looks down its local -Z with +Y up. The renderer's camera
    // has no roll and takes its aspect from the output size, so both are
    // reported when the file's differ.
    std::uint64_t orthographic_cameras = 0;
    bool rolled_camera = false;
    auto add_camera = [&](int camera_index, const std::string& node_name,
                          const glm::mat4& transform) {
        const auto& source = model.cameras[std::size_t(camera_index)];
        if (source.type != "perspective") {
            ++orthographic_cameras;
            return;
        }
        const glm::vec3 forward = glm::mat3(transform) * glm::vec3(0, 0, -1);
        const glm::vec3 up = glm::mat3(transform) * glm::vec3(0, 1, 0);
        const float forward_length = glm::length(forward);
        const double yfov = source.perspective.yfov;
        const double znear = source.perspective.znear;
        if (!(forward_length > 0.0f) || !std::isfinite(forward_length))
            reader.fail(fmt::format("camera {} has a degenerate node transform", camera_index));
        if (!(yfov > 0.0 && yfov < 3.14159) || !(znear > 0.0) || !std::isfinite(znear))
            reader.fail(
                fmt::format("camera {}: yfov must lie in (0, pi) and znear be > 0", camera_index));
        const glm::vec3 f = forward / forward_length;
        FileCamera file_camera;
        file_camera.index = camera_index;
        file_camera.name = source.name.empty() ? node_name : source.name;
        file_camera.camera.position = glm::vec3(transform * glm::vec4(0, 0, 0, 1));
        file_camera.camera.yaw = std::atan2(f.x, -f.z);
        file_camera.camera.pitch = std::asin(std::clamp(f.y, -1.0f, 1.0f));
        file_camera.camera.vertical_fov = float(yfov);
        file_camera.camera.near_plane = float(znear);
        const glm::vec3 right = glm::cross(f, glm::vec3(0, 1, 0));
        if (glm::length(right) > 1e-6f) {
            const glm::vec3 level_up = glm::normalize(glm::cross(glm::normalize(right), f));
            if (glm::dot(glm::normalize(up), level_up) < 0.9999f) rolled_camera = true;
        }
        scene.file_cameras.push_back(file_camera);
    };

    // KHR_lights_punctual: the renderer has one key light, directional, spot
    // or point. The first light met walking the nodes is it; every further
    // placement is named as dropped. The
    // extension's photometric units (lux, candela) become the renderer's
    // radiometric ones through 683 lm/W, the luminous efficacy the
    // extension's units are defined against.
    bool have_key_light = false;
    std::vector<std::string> dropped_lights;
    auto add_light = [&](int light_index, const glm::mat4& transform) {
        const auto& light = model.lights[std::size_t(light_index)];
        const std::string label = fmt::format(
            "{}{}", light_index, light.name.empty() ? "" : fmt::format(" '{}'", light.name));
        if (light.type != "directional" && light.type != "spot" && light.type != "point") {
            dropped_lights.push_back(fmt::format("{} ({}: unknown type)", label, light.type));
            return;
        }
        if (have_key_light) {
            dropped_lights.push_back(fmt::format("{} ({}, one key light only)", label, light.type));
            return;
        }
        const glm::vec3 direction = glm::mat3(transform) * glm::vec3(0, 0, -1);
        const float length = glm::length(direction);
        if (!(length > 0.0f) || !std::isfinite(length))
            reader.fail(fmt::format("light {} has a degenerate node transform", light_index));
        if (!(light.intensity >= 0.0) || !std::isfinite(light.intensity))
            reader.fail(
                fmt::format("light {}: intensity must be a finite number >= 0", light_index));
        KeyLight key;
        key.kind = light.type == "spot"    ? LightKind::spot
                   : light.type == "point" ? LightKind::point
                                           : LightKind::directional;
        key.direction = direction / length;
        key.position = glm::vec3(transform * glm::vec4(0, 0, 0, 1));
        key.colour = light.color.size() == 3
                         ? glm::vec3(light.color[0], light.color[1], light.color[2])
                         : glm::vec3(1.0f);
        key.intensity = float(light.intensity / 683.0);
        if (key.kind == LightKind::spot) {
            const double inner = light.spot.innerConeAngle, outer = light.spot.outerConeAngle;
            if (!(inner >= 0.0 && inner < outer && outer <= 1.5707963268))
                reader.fail(fmt::format(
                    "light {}: spot cone angles need 0 <= inner < outer <= pi/2", light_index));
            key.inner_cone = float(inner);
            key.outer_cone = float(outer);
        }
        if (key.kind != LightKind::directional && light.range != 0.0) {
            if (!(light.range > 0.0) || !std::isfinite(light.range))
                reader.fail(
                    fmt::format("light {}: range must be a finite number > 0", light_index));
            key.range = float(light.range);
        }
        scene.key_light = key;
        have_key_light = true;
    };

    // A node listed by several parents is visited once per path, so a few
    // nodes can describe 2^40 visits; the depth limit alone does not bound that.
    std::uint64_t visits = 0;
    std::function<void(int, const glm::mat4&, int)> visit =
        [&](int node_index, const glm::mat4& parent, int depth) {
            if (node_index < 0 || node_index >= int(model.nodes.size()))
                reader.fail("node index out of range");
            if (depth > 64) reader.fail("node hierarchy is too deep (cycle?)");
            if (++visits > limits.node_visits)
                reader.fail(fmt::format(
                    "the node graph expands to more than {} node visits (nodes shared by "
                    "several parents count once per path; raise with --scene-limit "
                    "node-visits=N)",
                    limits.node_visits));
            const auto& node = model.nodes[std::size_t(node_index)];
            const glm::mat4 transform = parent * node_transform(node);
            if (auto it = node.extensions.find("KHR_lights_punctual");
                it != node.extensions.end() && it->second.Has("light")) {
                const auto& value = it->second.Get("light");
                const int light = value.IsInt() ? value.Get<int>() : -1;
                if (light < 0 || light >= int(model.lights.size()))
                    reader.fail("KHR_lights_punctual light index out of range");
                add_light(light, transform);
            }
            if (node.camera >= 0) {
                if (node.camera >= int(model.cameras.size()))
                    reader.fail("camera index out of range");
                add_camera(node.camera, node.name, transform);
            }
            if (node.mesh >= 0) {
                if (node.mesh >= int(model.meshes.size())) reader.fail("mesh index out of range");
                for (const auto& primitive : model.meshes[std::size_t(node.mesh)].primitives)
                    add_primitive(primitive, transform);
            }
            for (int child : node.children) visit(child, transform, depth + 1);
        };

    if (!model.scenes.empty()) {
        const int scene_index =
            model.defaultScene >= 0 && model.defaultScene < int(model.scenes.size())
                ? model.defaultScene
                : 0;
        for (int node : model.scenes[std::size_t(scene_index)].nodes)
            visit(node, glm::mat4(1.0f), 0);
    } else {
        for (std::size_t i = 0; i < model.meshes.size(); ++i) {
            for (const auto& primitive : model.meshes[i].primitives)
                add_primitive(primitive, glm::mat4(1.0f));
        }
    }
    if (scene.vertices.empty())
        reader.fail(skipped_points_and_lines == 0
                        ? std::string("contains no triangles")
                        : fmt::format("contains no triangles (only {} point or line primitives)",
                                      skipped_points_and_lines));
    if (skipped_points_and_lines > 0)
        scene.warnings.push_back(
            fmt::format("skipped {} point or line primitive(s): they are not surfaces",
                        skipped_points_and_lines));

    // A glTF texture is an image plus a sampler; images are uploaded once,
    // samplers travel with the material that uses them.
    auto use_texture = [&](int texture_index, TextureSampler& sampler) {
        if (texture_index >= int(model.textures.size())) reader.fail("texture index out of range");
        const auto& texture = model.textures[std::size_t(texture_index)];
        const int image_index = texture.source;
        if (image_index < 0 || image_index >= int(model.images.size()))
            reader.fail("texture has no valid image");
        if (texture.sampler >= 0) {
            if (texture.sampler >= int(model.samplers.size()))
                reader.fail(fmt::format("texture {}: sampler index out of range", texture_index));
            sampler =
                read_sampler(model.samplers[std::size_t(texture.sampler)], texture.sampler, reader);
        }
        auto [it, inserted] = texture_of_image.try_emplace(image_index, int(scene.textures.size()));
        if (inserted)
            scene.textures.push_back(convert_image(model.images[std::size_t(image_index)], reader));
        return it->second;
    };

    std::uint64_t blended_materials = 0;
    for (auto& [material_index, indices] : indices_by_material) {
        Material material;
        if (material_index >= 0) {
            if (material_index >= int(model.materials.size()))
                reader.fail("material index out of range");
            const auto& source = model.materials[std::size_t(material_index)];
            const auto& factor = source.pbrMetallicRoughness.baseColorFactor;
            if (factor.size() == 4)
                material.base_colour = glm::vec4(factor[0], factor[1], factor[2], factor[3]);
            material.roughness = float(source.pbrMetallicRoughness.roughnessFactor);
            material.metallic = float(source.pbrMetallicRoughness.metallicFactor);
            if (source.emissiveFactor.size() == 3) {
                material.emissive = glm::vec3(source.emissiveFactor[0], source.emissiveFactor[1],
                                              source.emissiveFactor[2]);
            }
            // KHR_materials_emissive_strength scales the factor past 1.
            if (auto it = source.extensions.find("KHR_materials_emissive_strength");
                it != source.extensions.end() && it->second.Has("emissiveStrength")) {
                const auto& value = it->second.Get("emissiveStrength");
                const double strength = value.IsNumber() ? value.GetNumberAsDouble() : -1.0;
                if (!(strength >= 0.0) || !std::isfinite(strength))
                    reader.fail(
                        fmt::format("material {}: emissiveStrength must be a finite number >= 0",
                                    material_index));
                material.emissive *= float(strength);
            }
            if (source.alphaMode == "BLEND") {
                ++blended_materials;
            } else if (source.alphaMode == "MASK") {
                if (!(source.alphaCutoff >= 0.0) || !std::isfinite(source.alphaCutoff))
                    reader.fail(fmt::format("material {}: alphaCutoff must be a finite number >= 0",
                                            material_index));
                material.alpha_cutoff = float(source.alphaCutoff);
            } else if (source.alphaMode != "OPAQUE") {
                reader.fail(fmt::format("material {}: alphaMode '{}' is not OPAQUE, MASK or BLEND",
                                        material_index, source.alphaMode));
            }
            if (const int index = source.pbrMetallicRoughness.baseColorTexture.index; index >= 0)
                material.base_colour_texture = use_texture(index, material.base_colour_sampler);
            if (const int index = source.emissiveTexture.index; index >= 0)
                material.emissive_texture = use_texture(index, material.emissive_sampler);
        }
        scene.materials.push_back(material);
        DrawBatch batch;
        batch.first_index = static_cast<std::uint32_t>(scene.indices.size());
        batch.index_count = static_cast<std::uint32_t>(indices.size());
        batch.material = int(scene.materials.size()) - 1;
        scene.indices.insert(scene.indices.end(), indices.begin(), indices.end());
        scene.batches.push_back(batch);
    }

    if (blended_materials > 0)
        scene.warnings.push_back(fmt::format(
            "{} material(s) with alphaMode BLEND are rendered opaque", blended_materials));

    scene.bounds = compute_bounds(scene.vertices);
    const glm::vec3 centre = (scene.bounds.min + scene.bounds.max) * 0.5f;
    const float radius = std::max(glm::length(scene.bounds.max - scene.bounds.min) * 0.5f, 1e-3f);
    // Default view: from +z, a little above, far enough to see the bounding sphere.
    Camera camera;
    camera.vertical_fov = glm::radians(50.0f);
    camera.near_plane = std::max(radius * 1e-3f, 1e-4f);
    const float distance = radius / std::sin(camera.vertical_fov * 0.5f);
    camera.pitch = glm::radians(-15.0f);
    camera.position = centre - camera_forward(camera) * distance;
    scene.default_camera = camera;
    if (!scene.file_cameras.empty()) {
        scene.default_camera = scene.file_cameras.front().camera;
        if (rolled_camera)
            scene.warnings.push_back("camera roll is ignored (the view is levelled)");
    } else {
        scene.warnings.push_back("the file has no perspective camera; using a fitted view");
    }
    if (const std::string ignored = ignored_summary(model, orthographic_cameras); !ignored.empty())
        scene.warnings.push_back(ignored);
    scene.camera_path.frames_per_key = 30;
    for (int key = 0; key < 4; ++key) {  // orbit around the centre
        Camera orbit = camera;
        orbit.yaw = glm::radians(30.0f * float(key) - 45.0f);
        orbit.position = centre - camera_forward(orbit) * distance;
        scene.camera_path.keys.push_back(orbit);
    }
    if (!have_key_light) {
        scene.key_light.kind = LightKind::directional;
        scene.key_light.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
        scene.key_light.intensity = 3.0f;
    }
    if (!dropped_lights.empty()) {
        std::string list;
        for (const auto& light : dropped_lights) list += (list.empty() ? "" : ", ") + light;
        scene.warnings.push_back("dropped lights: " + list);
    }
    scene.ambient = glm::vec3(0.05f);
    scene.background = glm::vec3(0.2f, 0.22f, 0.25f);
    return scene;
}

}  // namespace

void set_scene_limit(SceneLimits& limits, std::string_view assignment) {
    const std::size_t equals = assignment.find('=');
    const std::string_view name = assignment.substr(0, equals);
    const std::string_view value =
        equals == std::string_view::npos ? std::string_view() : assignment.substr(equals + 1);
    std::uint64_t* target = nullptr;
    if (name == "json-depth")
        target = &limits.json_depth;
    else if (name == "node-visits")
        target = &limits.node_visits;
    else if (name == "triangles")
        target = &limits.triangles;
    else if (name == "texture-side")
        target = &limits.texture_side;
    else if (name == "texture-bytes")
        target = &limits.texture_bytes;
    if (target == nullptr || equals == std::string_view::npos)
        throw InputError(fmt::format(
            "--scene-limit '{}' is not NAME=VALUE with NAME one of json-depth, node-visits, "
            "triangles, texture-side, texture-bytes",
            assignment));
    *target = parse_limit_value(name, value);
}

Scene load_gltf_scene(const fs::path& path, const SceneLimits& limits) {
    if (!fs::exists(path))
        throw InputError(fmt::format("scene file '{}' does not exist", path.string()));
    if (!fs::is_regular_file(path))
        throw InputError(fmt::format("scene file '{}' is not a regular file", path.string()));
    const fs::path directory = path.has_parent_path() ? path.parent_path() : fs::path(".");
    tinygltf::Model model;
    {
        // One read of the whole file (a byte-wise istreambuf_iterator copy
        // costs a tenth of a second per 24 MB).
        std::error_code error;
        const std::uintmax_t size = fs::file_size(path, error);
        if (error || size > 0xffffffffu)
            throw InputError(fmt::format("cannot read scene file '{}': {}", path.string(),
                                         error ? error.message() : "larger than 4 GiB"));
        std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
        std::ifstream stream(path, std::ios::binary);
        if (!stream.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
            throw InputError(fmt::format("cannot read scene file '{}'", path.string()));
        // The content decides, not the name: a .glb holding JSON is read as JSON.
        const GltfKind kind = sniff_gltf(bytes);
        if (kind == GltfKind::none)
            throw InputError(
                fmt::format("scene file '{}' is not a glTF file (neither GLB magic "
                            "nor a JSON object)",
                            path.string()));
        model = parse_gltf(bytes, kind == GltfKind::binary, path.string(), directory.string(), true,
                           limits);
    }  // the file's bytes are freed before the scene is built
    Scene scene = build_scene(model, path.string(), path.stem().string(), limits);
    for (const auto& warning : scene.warnings)
        fmt::print(stderr, "warning: glTF file '{}': {}\n", path.string(), warning);
    return scene;
}

Scene load_gltf_scene_from_memory(std::span<const std::uint8_t> bytes, bool binary,
                                  std::string_view name, const SceneLimits& limits) {
    const tinygltf::Model model = parse_gltf(bytes, binary, std::string(name), "", false, limits);
    return build_scene(model, std::string(name), std::string(name), limits);
}

Camera find_file_camera(const Scene& scene, std::string_view name_or_index) {
    for (const auto& file_camera : scene.file_cameras)
        if (file_camera.name == name_or_index) return file_camera.camera;
    int index = -1;
    const auto [end, error] =
        std::from_chars(name_or_index.data(), name_or_index.data() + name_or_index.size(), index);
    if (error == std::errc() && end == name_or_index.data() + name_or_index.size()) {
        for (const auto& file_camera : scene.file_cameras)
            if (file_camera.index == index) return file_camera.camera;
    }
    std::string known;
    for (const auto& file_camera : scene.file_cameras)
        known += fmt::format("{}{} '{}'", known.empty() ? "" : ", ", file_camera.index,
                             file_camera.name);
    throw InputError(fmt::format("--camera '{}': scene '{}' has no such perspective camera ({})",
                                 name_or_index, scene.name,
                                 known.empty() ? "it has none" : "it has " + known));
}

Scene load_scene(std::string_view name_or_path, const SceneLimits& limits) {
    const fs::path path(name_or_path);
    // A built-in name wins over a file of that name in the working directory.
    for (const auto& builtin : builtin_scene_names())
        if (name_or_path == builtin) return make_builtin_scene(name_or_path);
    if (name_or_path.substr(0, 4) == "ref-") return make_builtin_scene(name_or_path);
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    // Named like glTF, or an existing file of any name: its content decides.
    if (extension == ".gltf" || extension == ".glb" || fs::exists(path))
        return load_gltf_scene(path, limits);
    return make_builtin_scene(name_or_path);
}

}  // namespace deepgi
