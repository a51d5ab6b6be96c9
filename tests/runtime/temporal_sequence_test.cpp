// The temporal filters' per-frame sample (shaders/temporal_sequence.h): the
// two-dimensional Sobol sequence, checked against a bit-by-bit evaluation of
// its definition written apart from the header, against its net property
// counted box by box, and on the GPU, which must compute the same bits from
// the same header.
#include "sao_test_support.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <cstdint>
#include <fstream>
#include <vector>

namespace deepgi::test {
namespace {

namespace shared {
using uint = std::uint32_t;
#define DEEPGI_SHARED_FUNCTION inline
#include "temporal_sequence.h"
#undef DEEPGI_SHARED_FUNCTION
}  // namespace shared

// Oracle for u: fraction bit r (bit 31 - r of the word) is bit r of k.
std::uint32_t radical_inverse_oracle(std::uint32_t k) {
    std::uint32_t u = 0;
    for (int r = 0; r < 32; ++r)
        if ((k >> r) & 1u) u |= 1u << (31 - r);
    return u;
}

// Oracle for v: the generator matrix of the second Sobol dimension is
// Pascal's triangle mod 2, entry (r, c) = binomial(c, r) mod 2, which by
// Lucas' theorem is 1 exactly when the bits of r are a subset of those of c.
// Fraction bit r of v is the parity of that row against the bits of k.
std::uint32_t pascal_oracle(std::uint32_t k) {
    std::uint32_t v = 0;
    for (std::uint32_t r = 0; r < 32; ++r) {
        std::uint32_t parity = 0;
        for (std::uint32_t c = 0; c < 32; ++c)
            if (((c & r) == r) && ((k >> c) & 1u)) parity ^= 1u;
        v |= parity << (31 - r);
    }
    return v;
}

// True when the points first .. first + 2^m - 1 put exactly one point in
// every box [i / 2^a, (i + 1) / 2^a) x [j / 2^b, (j + 1) / 2^b), a + b = m:
// a (0, m, 2)-net. `u` and `v` give the points as 32-bit fractions.
template <class U, class V>
bool is_zero_net(std::uint32_t first, int m, U u, V v) {
    const std::uint32_t count = 1u << m;
    for (int a = 0; a <= m; ++a) {
        const int b = m - a;
        std::vector<int> hits(count, 0);
        for (std::uint32_t n = 0; n < count; ++n) {
            const std::uint32_t k = first + n;  // the last run ends at 2^32 - 1
            const std::uint32_t i = a == 0 ? 0 : u(k) >> (32 - a);
            const std::uint32_t j = b == 0 ? 0 : v(k) >> (32 - b);
            ++hits[(i << b) | j];
        }
        for (int h : hits)
            if (h != 1) return false;
    }
    return true;
}

TEST_CASE("sequence: the frame sample is the Sobol sequence, computed apart from the header",
          "[sequence]") {
    // The first points from the direction numbers 1/2, 3/4, 5/8 (columns of
    // Pascal's triangle mod 2), by hand: the first frame keeps (0, 0).
    const std::array<double, 8> u_first = {0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
    const std::array<double, 8> v_first = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
    for (std::uint32_t k = 0; k < 8; ++k) {
        INFO("k = " << k);
        CHECK(double(shared::temporal_sequence_u_fixed(k)) * 0x1p-32 == u_first[k]);
        CHECK(double(shared::temporal_sequence_v_fixed(k)) * 0x1p-32 == v_first[k]);
    }
    // Every k below 2^16, and k spread over the whole 32-bit range.
    std::vector<std::uint32_t> ks;
    for (std::uint32_t k = 0; k < (1u << 16); ++k) ks.push_back(k);
    for (std::uint32_t i = 1; i <= 2000; ++i) ks.push_back(i * 0x9e3779b9u);
    ks.push_back(0xffffffffu);
    int u_mismatches = 0, v_mismatches = 0;
    for (std::uint32_t k : ks) {
        u_mismatches += shared::temporal_sequence_u_fixed(k) != radical_inverse_oracle(k);
        v_mismatches += shared::temporal_sequence_v_fixed(k) != pascal_oracle(k);
    }
    CHECK(ks.size() == 65536 + 2001);
    CHECK(u_mismatches == 0);
    CHECK(v_mismatches == 0);
}

TEST_CASE(
    "sequence: every aligned run of 2^m frames, m <= 8, is a (0, m, 2)-net, and the R2 sequence it "
    "replaced is not",
    "[sequence]") {
    const auto u = [](std::uint32_t k) { return shared::temporal_sequence_u_fixed(k); };
    const auto v = [](std::uint32_t k) { return shared::temporal_sequence_v_fixed(k); };
    for (int m = 0; m <= 8; ++m) {
        // The runs a still camera's history starts (first = 0) and later
        // ones, up to the top of the index range.
        for (std::uint32_t block : {0u, 1u, 2u, 3u, 77u, (0xffffffffu >> m)}) {
            INFO("m = " << m << ", run " << block);
            CHECK(is_zero_net(block << m, m, u, v));
        }
    }
    // The check can fail: R2, u = frac(k / g), v = frac(k / g^2), g the
    // plastic number, in the same fixed point, is not a net at 16 or 64
    // points; nor is the Sobol sequence started off a run's boundary.
    const auto r2_u = [](std::uint32_t k) { return k * 0xc13fa9a9u; };
    const auto r2_v = [](std::uint32_t k) { return k * 0x91e10da6u; };
    CHECK_FALSE(is_zero_net(0, 4, r2_u, r2_v));
    CHECK_FALSE(is_zero_net(0, 6, r2_u, r2_v));
    CHECK_FALSE(is_zero_net(1, 4, u, v));
}

TEST_CASE("sequence: the GPU computes the same bits from the same header", "[sequence]") {
    // The header is written in the common subset of GLSL and C++; this
    // compiles it as GLSL and compares every bit.
    HeadlessContext context;
    TemporaryFolder folder;
    std::ofstream(folder.path() / "sequence_probe.comp") << R"(#version 450 core
#define DEEPGI_SHARED_FUNCTION
#include "temporal_sequence.h"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 1) writeonly buffer Results { uvec2 results[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(indices.length())) return;
  results[i] = uvec2(temporal_sequence_u_fixed(indices[i]), temporal_sequence_v_fixed(indices[i]));
}
)";
    std::vector<std::uint32_t> ks;
    for (std::uint32_t k = 0; k < 4096; ++k) ks.push_back(k);
    for (std::uint32_t i = 1; i <= 2000; ++i) ks.push_back(i * 0x9e3779b9u);
    ks.push_back(0xffffffffu);
    const ShaderLoader loader = loader_with_override(folder.path());
    gl::Program program = loader.build_program({{GL_COMPUTE_SHADER, "sequence_probe.comp"}});
    gl::Buffer input = gl::create_buffer();
    gl::Buffer output = gl::create_buffer();
    glNamedBufferStorage(input.get(), GLsizeiptr(ks.size() * sizeof(ks[0])), ks.data(), 0);
    std::vector<std::array<std::uint32_t, 2>> results(ks.size());
    const GLsizeiptr result_bytes = GLsizeiptr(results.size() * sizeof(results[0]));
    glNamedBufferStorage(output.get(), result_bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, input.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, output.get());
    glUseProgram(program.get());
    glDispatchCompute(GLuint((ks.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(output.get(), 0, result_bytes, results.data());
    int mismatches = 0;
    for (std::size_t i = 0; i < ks.size(); ++i)
        mismatches +=
            results[i][0] != radical_inverse_oracle(ks[i]) || results[i][1] != pascal_oracle(ks[i]);
    CHECK(mismatches == 0);
}

}  // namespace
}  // namespace deepgi::test
