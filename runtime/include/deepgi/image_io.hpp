#pragma once
// Output files go through the shared atomic writer (fileio/): a failed run
// never leaves a half-written image behind, and special paths ("-", devices,
// symlinks) follow the rules in docs/hardening.md.
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

// The files' bytes in memory, so a caller can check every write of them.
// rgba8 rows bottom to top (GL order); encoded top to bottom as PNG expects.
std::vector<std::uint8_t> encode_png(int width, int height,
                                     const std::vector<std::uint8_t>& rgba8_bottom_up);
std::vector<std::uint8_t> encode_pfm(const FloatImage& image);

// rgba8 rows bottom to top (GL order); written top to bottom as PNG expects.
void write_png(const std::filesystem::path& path, int width, int height,
               const std::vector<std::uint8_t>& rgba8_bottom_up);
void write_pfm(const std::filesystem::path& path, const FloatImage& image);
FloatImage read_pfm(const std::filesystem::path& path);

}  // namespace deepgi
