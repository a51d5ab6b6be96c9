// The per-pixel rotation hash: the GPU computes the same bits as the CPU at
// 4K and beyond, and its angles show no structure across a 4K frame.
#include "sao_reference.hpp"
#include "sao_test_support.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <fstream>

namespace deepgi::test {
namespace {

constexpr int width_4k = 3840;
constexpr int height_4k = 2160;

// Evaluates pixel_rotation.glsl for a list of coordinates in a compute shader.
std::vector<std::array<std::uint32_t, 2>> gpu_hash_and_angle_bits(
    const std::vector<std::array<std::uint32_t, 2>>& pixels) {
    TemporaryFolder folder;
    std::ofstream(folder.path() / "rotation_probe.comp") << R"(#version 450 core
#include "pixel_rotation.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Pixels { uvec2 pixels[]; };
layout(std430, binding = 1) writeonly buffer Results { uvec2 results[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(pixels.length())) return;
  results[i] = uvec2(pixel_rotation_hash(pixels[i]), floatBitsToUint(pixel_rotation_angle(pixels[i])));
}
)";
    const ShaderLoader loader = loader_with_override(folder.path());
    gl::Program program = loader.build_program({{GL_COMPUTE_SHADER, "rotation_probe.comp"}});
    const GLsizeiptr bytes = GLsizeiptr(pixels.size() * sizeof(pixels[0]));
    gl::Buffer input = gl::create_buffer();
    gl::Buffer output = gl::create_buffer();
    glNamedBufferStorage(input.get(), bytes, pixels.data(), 0);
    glNamedBufferStorage(output.get(), bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, input.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, output.get());
    glUseProgram(program.get());
    glDispatchCompute(GLuint((pixels.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::array<std::uint32_t, 2>> results(pixels.size());
    glGetNamedBufferSubData(output.get(), 0, bytes, results.data());
    return results;
}

TEST_CASE(
    "rotation: the shared rotation hash gives MurmurHash3's finaliser values, computed "
    "apart from it",
    "[rotation]") {
    // The CPU reference includes the shader's own pixel_rotation_hash.h, a
    // piece shared between the oracle and the shader; so the hash is checked
    // here on its own, against values computed outside this code base from
    // its definition, h(x, y) = fmix32(x ^ fmix32(y + 0x9e3779b9)) with
    // MurmurHash3's 32-bit finaliser fmix32 (docs/deep-sao.md).
    // y = 2^32 - 0x9e3779b9 makes the inner fmix32(0) = 0, so h = fmix32(x):
    // fmix32(1) = 0x514e28b7 is MurmurHash3's published finaliser value, and
    // fmix32 fixes 0.
    constexpr std::uint32_t inner_zero = 0x61c88647u;
    CHECK(pixel_rotation_hash(1, inner_zero) == 0x514e28b7u);
    CHECK(pixel_rotation_hash(0, inner_zero) == 0u);
    CHECK(pixel_rotation_hash(0xdeadbeefu, inner_zero) == 0x0de5c6a9u);
    // Pixels of a frame, by an independent evaluation of the definition.
    CHECK(pixel_rotation_hash(0, 0) == 0xaa3e5b61u);
    CHECK(pixel_rotation_hash(1, 0) == 0x6f0b28e6u);
    CHECK(pixel_rotation_hash(0, 1) == 0x70f6c6d8u);
    CHECK(pixel_rotation_hash(3839, 2159) == 0xf1c06fb5u);
    CHECK(pixel_rotation_hash(12345, 678) == 0x1d539183u);
    CHECK(pixel_rotation_hash(16383, 16383) == 0xb9769785u);
}

TEST_CASE("rotation: the GPU rotation hash equals the CPU one bit for bit up to 16K",
          "[rotation]") {
    HeadlessContext context;
    std::vector<std::array<std::uint32_t, 2>> pixels;
    for (std::uint32_t y : {0u, 1u, 2159u, 2160u, 4095u, 8191u, 16383u}) {
        for (std::uint32_t x = 0; x < 16384; x += 37) pixels.push_back({x, y});
        for (std::uint32_t x : {3838u, 3839u, 3840u, 16383u}) pixels.push_back({x, y});
    }
    const auto results = gpu_hash_and_angle_bits(pixels);
    int hash_mismatches = 0;
    int angle_mismatches = 0;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        hash_mismatches += results[i][0] != pixel_rotation_hash(pixels[i][0], pixels[i][1]);
        const float angle = pixel_rotation_angle(pixels[i][0], pixels[i][1]);
        angle_mismatches += results[i][1] != std::bit_cast<std::uint32_t>(angle);
    }
    CHECK(hash_mismatches == 0);
    CHECK(angle_mismatches == 0);
}

// Structure a reconstruction blur cannot remove shows up as a lopsided angle
// histogram or as correlation between pixels a fixed step apart.
struct RotationQuality {
    double worst_bin_deviation = 0.0;  // relative, over 64 angle bins
    double worst_correlation = 0.0;    // |mean cos(phi(p) - phi(p + step))| over the steps
};

template <typename Angle>
RotationQuality measure_4k(Angle angle) {
    std::vector<float> phi(std::size_t(width_4k) * height_4k);
    std::array<double, 64> bins{};
    for (int y = 0; y < height_4k; ++y) {
        for (int x = 0; x < width_4k; ++x) {
            const float a = angle(std::uint32_t(x), std::uint32_t(y));
            phi[std::size_t(y) * width_4k + std::size_t(x)] = a;
            const double turns = std::fmod(double(a) / (2.0 * 3.141592653589793), 1.0);
            bins[std::min(63, int((turns < 0 ? turns + 1.0 : turns) * 64.0))] += 1.0;
        }
    }
    RotationQuality quality;
    const double expected = double(phi.size()) / 64.0;
    for (double count : bins)
        quality.worst_bin_deviation =
            std::max(quality.worst_bin_deviation, std::abs(count - expected) / expected);
    const std::array<std::array<int, 2>, 8> steps = {
        {{1, 0}, {0, 1}, {1, 1}, {1, -1}, {2, 0}, {0, 2}, {64, 0}, {0, 64}}};
    for (auto [dx, dy] : steps) {
        double sum = 0.0;
        std::size_t count = 0;
        for (int y = std::max(0, -dy); y < height_4k - std::max(0, dy); y += 3) {
            for (int x = 0; x < width_4k - dx; ++x) {
                sum += std::cos(double(phi[std::size_t(y) * width_4k + std::size_t(x)]) -
                                double(phi[std::size_t(y + dy) * width_4k + std::size_t(x + dx)]));
                ++count;
            }
        }
        quality.worst_correlation =
            std::max(quality.worst_correlation, std::abs(sum / double(count)));
    }
    return quality;
}

TEST_CASE("rotation: rotation angles over a 4K frame are uniform and uncorrelated", "[rotation]") {
    const RotationQuality quality = measure_4k(pixel_rotation_angle);
    INFO("worst bin deviation " << quality.worst_bin_deviation << ", worst correlation "
                                << quality.worst_correlation);
    CHECK(quality.worst_bin_deviation < 0.02);
    CHECK(quality.worst_correlation < 0.01);
}

TEST_CASE("rotation: the checks above catch a rotation built on the product of the coordinates",
          "[rotation]") {
    // x * y * odd constant (mod 2^32): what a hash inherits from products of
    // pixel coordinates; row 0 and column 0 are all one angle, and rows whose y
    // shares a power of two share structure.
    const RotationQuality quality = measure_4k([](std::uint32_t x, std::uint32_t y) {
        return float((x * y * 2654435761u) >> 8) * (1.0f / 16777216.0f) * 6.2831855f;
    });
    INFO("worst bin deviation " << quality.worst_bin_deviation << ", worst correlation "
                                << quality.worst_correlation);
    CHECK((quality.worst_bin_deviation >= 0.02 || quality.worst_correlation >= 0.01));
}

}  // namespace
}  // namespace deepgi::test
