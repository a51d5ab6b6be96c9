// The glTF loader's images: decoded within the texture limits, converted to
// RGBA8, with their samplers.
#include "gltf_internal.hpp"

#include <stb_image.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <optional>

namespace deepgi::gltf {

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

namespace {

struct PngChunk {
    std::size_t offset = 0;
    std::uint32_t length = 0;
};

// The first chunk of a PNG whose length field runs past the end of the file,
// if any. stb_image grows its buffer for the compressed data to a chunk's
// claimed length before it reads the chunk, so a 200-byte file whose IDAT
// claims 1 GiB asked for 2 GiB; a chunk is only handed over once it is
// proved inside the bytes. Not a PNG: nothing to check here.
std::optional<PngChunk> png_chunk_past_end(const unsigned char* bytes, std::size_t size) {
    static constexpr unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (size < 8 || std::memcmp(bytes, signature, 8) != 0) return std::nullopt;
    std::size_t offset = 8;
    // length (4 bytes, big-endian), type (4), data (length), CRC (4)
    while (size - offset >= 8) {
        const std::uint32_t length = std::uint32_t(bytes[offset]) << 24 |
                                     std::uint32_t(bytes[offset + 1]) << 16 |
                                     std::uint32_t(bytes[offset + 2]) << 8 | bytes[offset + 3];
        if (length > size - offset - 8 || size - offset - 8 - length < 4)
            return PngChunk{offset, length};
        if (std::memcmp(bytes + offset + 4, "IEND", 4) == 0) break;
        offset += 12 + std::size_t(length);
    }
    return std::nullopt;
}

}  // namespace

// tinygltf decodes every image while it parses; this decoder checks each
// image's size from its header first, so a 300 KB PNG cannot ask for
// gigabytes. Images always come out as 8 bits per channel.
bool load_image_within_limits(tinygltf::Image* image, int image_index, std::string* error,
                              std::string*, int, int, const unsigned char* bytes, int size,
                              void* user_data) {
    auto& budget = *static_cast<ImageBudget*>(user_data);
    const SceneLimits& limits = *budget.limits;
    // tinygltf hands an image stored in a buffer view over as the address of
    // byte byteOffset with byteLength bytes, checking neither against the
    // buffer: the view is proved inside its buffer here, and the decoder gets
    // exactly its bytes.
    if (image->bufferView >= 0) {
        auto refuse = [&](const std::string& what) {
            if (error) *error += fmt::format("image {}: {}. ", image_index, what);
            return false;
        };
        const auto& model = *budget.model;
        const std::size_t view_index = std::size_t(image->bufferView);
        if (view_index >= model.bufferViews.size())
            return refuse(fmt::format("buffer view {} does not exist", view_index));
        const auto& view = model.bufferViews[view_index];
        if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size())
            return refuse(fmt::format("buffer view {} names a missing buffer", view_index));
        const auto& buffer = model.buffers[std::size_t(view.buffer)];
        std::size_t end = 0;
        if (__builtin_add_overflow(view.byteOffset, view.byteLength, &end) ||
            end > buffer.data.size())
            return refuse(fmt::format(
                "buffer view {} (byteOffset {}, byteLength {}) runs past its buffer's {} bytes",
                view_index, view.byteOffset, view.byteLength, buffer.data.size()));
        if (view.byteLength > std::size_t(std::numeric_limits<int>::max()))
            return refuse(fmt::format("buffer view {} is larger than 2 GiB", view_index));
        bytes = buffer.data.data() + view.byteOffset;
        size = int(view.byteLength);
    }
    if (bytes == nullptr || size <= 0) {
        if (error) *error += fmt::format("image {} is empty. ", image_index);
        return false;
    }
    if (const auto chunk = png_chunk_past_end(bytes, std::size_t(size))) {
        if (error)
            *error += fmt::format(
                "image {}: a PNG chunk at byte {} claims {} bytes, past the end of the image's {} "
                "bytes. ",
                image_index, chunk->offset, chunk->length, size);
        return false;
    }
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

}  // namespace deepgi::gltf
