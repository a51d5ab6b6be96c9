#pragma once
// Output files are written to a temporary name and renamed, so a failed run
// never leaves a half-written image behind.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace deepgi {

// Float image, rows bottom to top (GL and PFM order).
struct FloatImage {
    int width = 0;
    int height = 0;
    int channels = 1;  // 1 or 3
    std::vector<float> pixels;
    float at(int x, int y, int c = 0) const {
        return pixels[(std::size_t(y) * width + x) * channels + c];
    }
};

// rgba8 rows bottom to top (GL order); written top to bottom as PNG expects.
void write_png(const std::filesystem::path& path, int width, int height,
               const std::vector<std::uint8_t>& rgba8_bottom_up);
void write_pfm(const std::filesystem::path& path, const FloatImage& image);
FloatImage read_pfm(const std::filesystem::path& path);

}  // namespace deepgi
