// The glTF loader's checked reader and limits: accessor reads proved inside
// their buffers with overflow-checked arithmetic, the JSON depth scan, and
// the --scene-limit values.
#include "gltf_internal.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstring>

namespace deepgi::gltf {

std::string one_line(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    std::replace(text.begin(), text.end(), '\r', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    // Other control bytes (a NUL from a decoded URI) are written visibly.
    std::string visible;
    for (const char c : text) {
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t')
            visible += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
        else
            visible += c;
    }
    return visible;
}

std::function<float(std::size_t, int)> GltfReader::accessor_reader(
    int accessor_index, int expected_components, std::size_t& count,
    std::pair<const std::uint8_t*, std::size_t>* raw) const {
    if (accessor_index < 0 || accessor_index >= int(model_.accessors.size()))
        fail("accessor index out of range");
    const auto& accessor = model_.accessors[std::size_t(accessor_index)];
    // Valid glTF, but its values replace elements of the base view: reading
    // the view alone would draw the wrong geometry without a word.
    if (accessor.sparse.isSparse)
        fail(fmt::format("accessor {} is sparse; sparse accessors are not supported",
                         accessor_index));
    const int components =
        tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
    if (components != expected_components)
        fail(fmt::format("accessor {} has {} components, expected {}", accessor_index, components,
                         expected_components));
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
        fail(fmt::format("{}: its buffer view ends at byte {}, past the buffer's {} bytes", subject,
                         view_end, buffer.data.size()));
    const std::size_t begin =
        checked.add(view.byteOffset, accessor.byteOffset, "bufferView + accessor byteOffset");
    if (begin > view_end)
        fail(fmt::format("{}: starts at byte {}, past the end of its buffer view at byte {}",
                         subject, begin, view_end));
    if (count > 0) {
        const std::size_t span = checked.add(checked.mul(count - 1, stride, "count x byteStride"),
                                             element_size, "count x byteStride + element size");
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

std::vector<std::uint32_t> GltfReader::read_indices(int accessor_index) const {
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

std::string malformed_uri(std::string_view json) {
    // The string starting at the quote json[at], raw (escapes kept); `at`
    // ends on its closing quote.
    auto string_at = [&](std::size_t& at) {
        const std::size_t begin = ++at;
        while (at < json.size() && json[at] != '"') at += json[at] == '\\' ? 2 : 1;
        return json.substr(begin, std::min(at, json.size()) - begin);
    };
    auto skip_blanks = [&](std::size_t& at) {
        while (at < json.size() && std::isspace(static_cast<unsigned char>(json[at]))) ++at;
    };
    auto hex = [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; };
    for (std::size_t i = 0; i < json.size(); ++i) {
        if (json[i] != '"') continue;
        if (string_at(i) != "uri") continue;
        std::size_t at = i + 1;
        skip_blanks(at);
        if (at >= json.size() || json[at] != ':') continue;
        ++at;
        skip_blanks(at);
        if (at >= json.size() || json[at] != '"') continue;
        const std::string_view uri = string_at(at);
        i = at;
        if (uri.substr(0, 5) == "data:") continue;
        for (std::size_t k = 0; k < uri.size(); ++k) {
            if (uri[k] != '%') continue;
            if (k + 2 >= uri.size())
                return fmt::format("URI '{}' ends in an incomplete percent-escape",
                                   one_line(std::string(uri)));
            if (!hex(uri[k + 1]) || !hex(uri[k + 2]))
                return fmt::format("URI '{}' has a malformed percent-escape '{}'",
                                   one_line(std::string(uri)), uri.substr(k, 3));
            if (uri[k + 1] == '0' && uri[k + 2] == '0')
                return fmt::format("URI '{}' has the percent-escape %00 (NUL)",
                                   one_line(std::string(uri)));
            k += 2;
        }
    }
    return "";
}

static std::uint32_t read_u32_le(const std::uint8_t* p) {
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

}  // namespace deepgi::gltf

namespace deepgi {

void set_scene_limit(SceneLimits& limits, std::string_view assignment) {
    const std::size_t equals = assignment.find('=');
    const std::string_view name = assignment.substr(0, equals);
    const std::string_view value =
        equals == std::string_view::npos ? std::string_view() : assignment.substr(equals + 1);
    struct Named {
        std::string_view name;
        std::uint64_t* value;
    };
    const Named all[] = {
        {"json-depth", &limits.json_depth},         {"node-visits", &limits.node_visits},
        {"triangles", &limits.triangles},           {"texture-side", &limits.texture_side},
        {"texture-bytes", &limits.texture_bytes},   {"instances", &limits.instances},
        {"geometry-bytes", &limits.geometry_bytes}, {"load-seconds", &limits.load_seconds},
        {"file-bytes", &limits.file_bytes}};
    std::uint64_t* target = nullptr;
    std::string names;
    for (const auto& named : all) {
        if (named.name == name) target = named.value;
        names += fmt::format("{}{}", names.empty() ? "" : ", ", named.name);
    }
    if (target == nullptr || equals == std::string_view::npos)
        throw InputError(fmt::format("--scene-limit '{}' is not NAME=VALUE with NAME one of {}",
                                     assignment, names));
    *target = gltf::parse_limit_value(name, value);
}

}  // namespace deepgi
