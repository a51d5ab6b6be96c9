#include "deepgi/image_io.hpp"

#include "deepgi/errors.hpp"

#include <fmt/format.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <system_error>

namespace deepgi {

namespace fs = std::filesystem;

namespace {

fs::path temporary_sibling(const fs::path& path) {
    return fs::path(path.string() + fmt::format(".tmp{}", static_cast<long>(::getpid())));
}

// Rename is atomic within a directory: readers see the old file or the whole new one.
void commit(const fs::path& temporary, const fs::path& path) {
    std::error_code error;
    fs::rename(temporary, path, error);
    if (error) {
        fs::remove(temporary, error);
        throw InputError(fmt::format("cannot write '{}': {}", path.string(), error.message()));
    }
}

}  // namespace

void write_png(const fs::path& path, int width, int height,
               const std::vector<std::uint8_t>& rgba8_bottom_up) {
    const fs::path temporary = temporary_sibling(path);
    // stb writes rows top to bottom; GL gave them bottom to top.
    const std::size_t stride = std::size_t(width) * 4;
    std::vector<std::uint8_t> top_down(rgba8_bottom_up.size());
    for (int y = 0; y < height; ++y) {
        std::memcpy(top_down.data() + std::size_t(y) * stride,
                    rgba8_bottom_up.data() + std::size_t(height - 1 - y) * stride, stride);
    }
    if (stbi_write_png(temporary.string().c_str(), width, height, 4, top_down.data(),
                       int(stride)) == 0) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw InputError(fmt::format("cannot write PNG '{}'", path.string()));
    }
    commit(temporary, path);
}

void write_pfm(const fs::path& path, const FloatImage& image) {
    const fs::path temporary = temporary_sibling(path);
    {
        std::ofstream stream(temporary, std::ios::binary);
        if (!stream) throw InputError(fmt::format("cannot write PFM '{}'", path.string()));
        // Negative scale: little-endian floats. Rows bottom to top, as PFM defines.
        stream << (image.channels == 3 ? "PF" : "Pf") << "\n"
               << image.width << " " << image.height << "\n-1.0\n";
        stream.write(reinterpret_cast<const char*>(image.pixels.data()),
                     static_cast<std::streamsize>(image.pixels.size() * sizeof(float)));
        if (!stream) {
            stream.close();
            std::error_code ignored;
            fs::remove(temporary, ignored);
            throw InputError(fmt::format("cannot write PFM '{}'", path.string()));
        }
    }
    commit(temporary, path);
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
