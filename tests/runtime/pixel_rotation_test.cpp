// The per-pixel rotation hash: the GPU computes the same bits as the CPU at
// 4K and beyond, and its angles show no structure across a 4K frame.
#include "sao_reference.hpp"
#include "sao_test_support.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <fstream>
#include <optional>

namespace deepgi::test {
namespace {

constexpr int width_4k = 3840;
constexpr int height_4k = 2160;

// Evaluates pixel_rotation.glsl for a list of coordinates in a compute shader,
// with the rotation seed `seed`.
std::vector<std::array<std::uint32_t, 2>> gpu_hash_and_angle_bits(
    const std::vector<std::array<std::uint32_t, 2>>& pixels, std::uint32_t seed = 0) {
    TemporaryFolder folder;
    std::ofstream(folder.path() / "rotation_probe.comp") << R"(#version 450 core
#include "pixel_rotation.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Pixels { uvec2 pixels[]; };
layout(std430, binding = 1) writeonly buffer Results { uvec2 results[]; };
layout(location = 0) uniform uint seed;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(pixels.length())) return;
  results[i] = uvec2(pixel_rotation_hash(pixels[i], seed), floatBitsToUint(pixel_rotation_angle(pixels[i], seed)));
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
    glProgramUniform1ui(program.get(), 0, seed);
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

TEST_CASE(
    "rotation: a rotation seed joins the hash as h(x, y) ^ fmix32(seed) inside the outer "
    "finaliser, computed apart from it",
    "[rotation]") {
    // Definition: h_s(x, y) = fmix32(x ^ fmix32(y + 0x9e3779b9) ^ fmix32(s)).
    // fmix32(0) = 0, so seed 0 is the unseeded hash above (the shipped field).
    constexpr std::uint32_t inner_zero = 0x61c88647u;
    CHECK(pixel_rotation_hash(0, 0, 0) == 0xaa3e5b61u);
    CHECK(pixel_rotation_hash(3839, 2159, 0) == 0xf1c06fb5u);
    // With x = 0 and the inner term 0 it is fmix32(fmix32(1)) = fmix32(0x514e28b7).
    CHECK(pixel_rotation_hash(0, inner_zero, 1) == 0x2fef5c8fu);
    // Pixels of a frame, by an independent evaluation of the definition.
    CHECK(pixel_rotation_hash(0, 0, 1) == 0xafa866e6u);
    CHECK(pixel_rotation_hash(1, 0, 1) == 0x9e1d436bu);
    CHECK(pixel_rotation_hash(0, 1, 1) == 0xe5624b7du);
    CHECK(pixel_rotation_hash(3839, 2159, 1) == 0xa3f99029u);
    CHECK(pixel_rotation_hash(12345, 678, 7) == 0x9c28e20bu);
    CHECK(pixel_rotation_hash(16383, 16383, 1u << 20) == 0xe805af94u);
}

TEST_CASE("rotation: a seeded GPU rotation hash equals the CPU one bit for bit", "[rotation]") {
    HeadlessContext context;
    std::vector<std::array<std::uint32_t, 2>> pixels;
    for (std::uint32_t y : {0u, 1u, 719u, 2159u, 16383u}) {
        for (std::uint32_t x = 0; x < 16384; x += 101) pixels.push_back({x, y});
    }
    for (std::uint32_t seed : {1u, 2u, 7u, 1u << 20}) {
        const auto results = gpu_hash_and_angle_bits(pixels, seed);
        int hash_mismatches = 0;
        int angle_mismatches = 0;
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            hash_mismatches +=
                results[i][0] != pixel_rotation_hash(pixels[i][0], pixels[i][1], seed);
            const float angle = pixel_rotation_angle(pixels[i][0], pixels[i][1], seed);
            angle_mismatches += results[i][1] != std::bit_cast<std::uint32_t>(angle);
        }
        INFO("seed " << seed);
        CHECK(hash_mismatches == 0);
        CHECK(angle_mismatches == 0);
    }
}

TEST_CASE("rotation: every seed of the report's repeats gives a field unrelated to seed 0",
          "[rotation]") {
    // The report's repeats (repeat_rotation_seed: seed r) only measure the
    // noise of the per-pixel field if each seed's angles are new at almost
    // every pixel and carry no trace of the seed-0 angle there: a seed that
    // merely shifted or reflected the field would keep the correlation at 1.
    for (std::uint32_t seed : {1u, 2u, 3u, 15u, 1u << 20}) {
        long long same = 0;
        long long count = 0;
        double sum_cos = 0.0;
        for (std::uint32_t y = 0; y < std::uint32_t(height_4k); y += 7) {
            for (std::uint32_t x = 0; x < std::uint32_t(width_4k); ++x) {
                const float a = pixel_rotation_angle(x, y);
                const float b = pixel_rotation_angle(x, y, seed);
                same += a == b;
                sum_cos += std::cos(double(a) - double(b));
                ++count;
            }
        }
        const double correlation = sum_cos / double(count);
        INFO("seed " << seed << ": " << same << " of " << count << " pixels keep their angle, "
                     << "mean cos(phi_0 - phi_s) " << correlation);
        CHECK(double(same) < 1e-4 * double(count));
        // 1.2M pixels: the mean of cos over independent angles has a standard
        // deviation of 0.00065; 0.005 is over 7 of them.
        CHECK(std::abs(correlation) < 0.005);
    }
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

// The fraction of surface pixels where two renders' channel 0 differs,
// leaving out the pixels where both equal `unaffected` (an AO of exactly 1:
// nothing occludes within the radius, whichever way the taps turn).
double fraction_changed(const FloatImage& a, const FloatImage& b, const FloatImage& depth,
                        std::optional<float> unaffected = std::nullopt) {
    long long surface = 0;
    long long changed = 0;
    for (int y = 0; y < depth.height; ++y) {
        for (int x = 0; x < depth.width; ++x) {
            if (depth.at(x, y, 0) <= 0.0f) continue;
            if (unaffected && a.at(x, y, 0) == *unaffected && b.at(x, y, 0) == *unaffected)
                continue;
            ++surface;
            changed += a.at(x, y, 0) != b.at(x, y, 0);
        }
    }
    REQUIRE(surface > 1000);
    return double(changed) / double(surface);
}

TEST_CASE("rotation: the rotation-seed setting reaches the gathers, and seed 0 is the default",
          "[rotation]") {
    const RenderSettings settings = small_settings(160, 90);
    CornellRenderer cornell(settings);
    Renderer& renderer = cornell.renderer;
    auto render = [&](int seed) {
        RenderSettings s = settings;
        s.rotation_seed = seed;
        renderer.set_settings(s);
        renderer.render(cornell.scene.default_camera, CameraMotion::cut);
        return std::array{renderer.read_pass_output("ao-raw"),
                          renderer.read_pass_output("radiosity-blurred")};
    };
    const auto shipped = render(0);
    const FloatImage depth = renderer.read_pass_output("gbuffer-depth-layer0");
    const auto seeded = render(3);
    const auto shipped_again = render(0);
    // Seed 0 after seed 3 renders the first frame again, bit for bit.
    CHECK(shipped_again[0].pixels == shipped[0].pixels);
    CHECK(shipped_again[1].pixels == shipped[1].pixels);
    // Every pixel turns its spiral by another angle: the raw AO (where
    // anything occludes) and the gathered radiosity change almost everywhere.
    const double ao_changed = fraction_changed(shipped[0], seeded[0], depth, 1.0f);
    const double radiosity_changed = fraction_changed(shipped[1], seeded[1], depth);
    INFO("seed 3 against seed 0: raw AO differs at " << ao_changed << " of the occluded surface, "
                                                     << "blurred radiosity at " << radiosity_changed
                                                     << " of the surface");
    CHECK(ao_changed > 0.8);
    CHECK(radiosity_changed > 0.8);
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
    const RotationQuality quality =
        measure_4k([](std::uint32_t x, std::uint32_t y) { return pixel_rotation_angle(x, y); });
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
