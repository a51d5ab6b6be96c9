#include "deepgi/image_io.hpp"

#include "deepgi/errors.hpp"

#include <fmt/format.h>
#include <spiral/fileio.hpp>
#include <stb_image_write.h>

#include <cstring>
#include <fstream>
#include <system_error>

namespace deepgi {

namespace fs = std::filesystem;

std::vector<std::uint8_t> encode_png(int width, int height,
                                     const std::vector<std::uint8_t>& rgba8_bottom_up) {
    // stb writes rows top to bottom; GL gave them bottom to top.
    const std::size_t stride = std::size_t(width) * 4;
    std::vector<std::uint8_t> top_down(rgba8_bottom_up.size());
    for (int y = 0; y < height; ++y) {
        std::memcpy(top_down.data() + std::size_t(y) * stride,
                    rgba8_bottom_up.data() + std::size_t(height - 1 - y) * stride, stride);
    }
    // stb's callback appends to our buffer; the file itself is written by
    // the atomic writer, which checks every write (stb's own file output
    // ignores write errors, so a full disk gave a truncated PNG and exit 0).
    std::vector<std::uint8_t> png;
    auto append = [](void* context, void* data, int size) {
        auto& out = *static_cast<std::vector<std::uint8_t>*>(context);
        const auto* bytes = static_cast<const std::uint8_t*>(data);
        out.insert(out.end(), bytes, bytes + size);
    };
    if (stbi_write_png_to_func(append, &png, width, height, 4, top_down.data(), int(stride)) == 0)
        throw InputError(fmt::format("cannot encode a {}x{} PNG", width, height));
    return png;
}

std::vector<std::uint8_t> encode_pfm(const FloatImage& image) {
    // Negative scale: little-endian floats. Rows bottom to top, as PFM defines.
    const std::string header = fmt::format("{}\n{} {}\n-1.0\n", image.channels == 3 ? "PF" : "Pf",
                                           image.width, image.height);
    std::vector<std::uint8_t> bytes(header.begin(), header.end());
    const auto* pixels = reinterpret_cast<const std::uint8_t*>(image.pixels.data());
    bytes.insert(bytes.end(), pixels, pixels + image.pixels.size() * sizeof(float));
    return bytes;
}

void write_png(const fs::path& path, int width, int height,
               const std::vector<std::uint8_t>& rgba8_bottom_up) {
    const auto png = encode_png(width, height, rgba8_bottom_up);
    spiral::fileio::AtomicFile file(path);
    file.write(png.data(), png.size());
    file.commit();
}

void write_pfm(const fs::path& path, const FloatImage& image) {
    const auto pfm = encode_pfm(image);
    spiral::fileio::AtomicFile file(path);
    file.write(pfm.data(), pfm.size());
    file.commit();
}

FloatImage read_pfm(const fs::path& path) {
    std::ifstream stream(path, std::ios::binary);
    if (!stream) throw InputError(fmt::format("cannot read PFM '{}'", path.string()));
    std::string magic;
    FloatImage image;
    float scale = 0.0f;
    stream >> magic >> image.width >> image.height >> scale;
    stream.get();  // the single whitespace before the data
    if (!stream || (magic != "PF" && magic != "Pf") || image.width <= 0 || image.height <= 0 ||
        scale >= 0.0f) {
        throw InputError(fmt::format("'{}' is not a little-endian PFM file", path.string()));
    }
    image.channels = magic == "PF" ? 3 : 1;
    image.pixels.resize(std::size_t(image.width) * std::size_t(image.height) *
                        std::size_t(image.channels));
    stream.read(reinterpret_cast<char*>(image.pixels.data()),
                static_cast<std::streamsize>(image.pixels.size() * sizeof(float)));
    if (!stream) throw InputError(fmt::format("PFM '{}' is truncated", path.string()));
    return image;
}

}  // namespace deepgi
