// The bilateral blur on hand-made guides, where the right answer is known
// without running a blur: constants stay constant, steps and creases stay
// sharp, a flat plane gives back the generated Gaussian. On rough guides
// (fractional weights everywhere) against a CPU evaluation of the same
// formula (blur_reference.cpp), for one source and for two sources sharing
// one set of weights.
#include "blur_reference.hpp"
#include "deepgi/errors.hpp"
#include "passes/passes.hpp"
#include "sao_test_support.hpp"
#include "shader_shared.hpp"

#include <catch2/catch.hpp>

#include <numeric>

namespace deepgi::test {
namespace {

// The second source's own reach (BilateralBlur::second_extent_start) and the
// frame it is read at; start 0: it shares the first's.
struct SecondReach {
    float start = 0.0f;
    int temporal_frame = 0;
};

// Runs the blur on every source at once (one blur, shared weights) and
// returns the outputs, in the sources' order. Float formats throughout, so
// only the blur's arithmetic separates it from the CPU evaluation.
std::vector<Signal> run_blur_sources(const ShaderLoader& loader, const Guide& guide,
                                     const std::vector<Signal>& sources,
                                     const BilateralBlurParameters& parameters = {},
                                     float world_extent = 0.0f, const SecondReach& second = {}) {
    const int w = guide.width;
    const int h = guide.height;
    shader_shared::FrameConstants constants{};
    constants.temporal_frame = second.temporal_frame;
    constants.internal_size = {float(w), float(h), 1.0f / float(w), 1.0f / float(h)};
    constants.camera_ray_scale = {0.7f, 0.45f, 0.05f, 0.0f};
    gl::Buffer frame = gl::create_buffer();
    glNamedBufferStorage(frame.get(), sizeof(constants), &constants, 0);
    glBindBufferBase(GL_UNIFORM_BUFFER, DEEPGI_UBO_FRAME, frame.get());

    std::vector<float> depth_rg;
    std::vector<float> normal_rg;
    for (std::size_t i = 0; i < guide.depth.size(); ++i) {
        depth_rg.insert(depth_rg.end(), {guide.depth[i], 0.0f});
        const glm::vec2 e = encode_octahedral(guide.normal[i]);
        normal_rg.insert(normal_rg.end(), {e.x, e.y});
    }
    gl::Texture depth = gl::create_texture_2d(GL_RG32F, w, h);
    glTextureSubImage2D(depth.get(), 0, 0, 0, w, h, GL_RG, GL_FLOAT, depth_rg.data());
    gl::Texture normal = gl::create_texture_array(GL_RG16F, w, h, 2);
    glTextureSubImage3D(normal.get(), 0, 0, 0, 0, w, h, 1, GL_RG, GL_FLOAT, normal_rg.data());
    std::vector<gl::Texture> inputs;
    std::vector<GLuint> input_names;
    std::vector<GLenum> formats;
    for (const Signal& source : sources) {
        const bool rgba = source.channels == 4;
        formats.push_back(rgba ? GL_RGBA32F : GL_R32F);
        inputs.push_back(gl::create_texture_2d(formats.back(), w, h));
        glTextureSubImage2D(inputs.back().get(), 0, 0, 0, w, h, rgba ? GL_RGBA : GL_RED, GL_FLOAT,
                            source.values.data());
        input_names.push_back(inputs.back().get());
    }
    gl::VertexArray empty = gl::create_vertex_array();

    BilateralBlur blur = create_bilateral_blur(loader, int(sources.size()), parameters);
    blur.world_extent = world_extent;
    blur.second_extent_start = second.start;
    resize_bilateral_blur(blur, w, h, formats);
    run_bilateral_blur(blur, input_names, depth.get(), normal.get(), empty.get());
    std::vector<Signal> outputs;
    const GLuint textures[] = {blur.output.get(), blur.second_output.get()};
    for (std::size_t i = 0; i < sources.size(); ++i) {
        Signal output{sources[i].channels, std::vector<float>(sources[i].values.size())};
        glGetTextureImage(textures[i], 0, output.channels == 4 ? GL_RGBA : GL_RED, GL_FLOAT,
                          GLsizei(output.values.size() * sizeof(float)), output.values.data());
        outputs.push_back(std::move(output));
    }
    return outputs;
}

// Runs the pass on `source` (one float per pixel) and returns the output.
std::vector<float> run_blur(const ShaderLoader& loader, const Guide& guide,
                            const std::vector<float>& source,
                            const BilateralBlurParameters& parameters = {},
                            float world_extent = 0.0f) {
    return run_blur_sources(loader, guide, {Signal{1, source}}, parameters, world_extent)
        .front()
        .values;
}

// The build's kernel (blur_kernel.glsl as CMake generated it).
spiral::codegen::BlurKernel build_kernel() {
    const std::string build_sigma = SAO_TEST_BLUR_SIGMA;
    return spiral::codegen::gaussian_kernel(
        SAO_TEST_BLUR_RADIUS,
        build_sigma.empty() ? std::nullopt : std::optional(std::stod(build_sigma)));
}

std::vector<float> random_values(std::size_t count, unsigned seed) {
    std::mt19937 generator(seed);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    std::vector<float> values(count);
    for (float& value : values) value = uniform(generator);
    return values;
}

// Tiles of different depth and orientation, and some sky.
Guide patchwork(int width, int height) {
    return make_guide(width, height, [](int x, int y) -> std::pair<float, glm::vec3> {
        const int tile = (x / 7) * 31 + (y / 5) * 17;
        if (tile % 11 == 3) return {0.0f, {0, 0, 1}};
        return {1.0f + float(tile % 5) * 0.7f,
                {float(tile % 3) - 1.0f, float(tile % 4) * 0.3f - 0.4f, 1.0f}};
    });
}

// Tiles as in patchwork, each a tilted plane with slightly wavy normals, so
// that taps within a tile get depth, normal and plane weights strictly
// between 0 and 1.
Guide rough_patchwork(int width, int height) {
    return make_guide(width, height, [](int x, int y) -> std::pair<float, glm::vec3> {
        const int tile = (x / 9) * 31 + (y / 7) * 17;
        if (tile % 11 == 3) return {0.0f, {0, 0, 1}};
        const float depth = 1.0f + float(tile % 5) * 0.7f + 0.004f * float(x) - 0.003f * float(y);
        return {depth,
                {float(tile % 3) - 1.0f + 0.08f * std::sin(float(x)),
                 float(tile % 4) * 0.3f - 0.4f + 0.08f * std::cos(float(y) * 1.3f), 1.0f}};
    });
}

float max_difference(const std::vector<float>& a, const std::vector<float>& b) {
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
    return worst;
}

TEST_CASE("blur: the blur preserves a constant image, borders and sky included", "[blur]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    for (auto [w, h] : {std::pair{64, 40}, std::pair{5, 3}, std::pair{1, 1}}) {
        const Guide guide = patchwork(w, h);
        const std::vector<float> constant(std::size_t(w) * std::size_t(h), 0.3721f);
        INFO(w << "x" << h);
        CHECK(max_difference(run_blur(loader, guide, constant), constant) <= 1e-6f);
    }
}

TEST_CASE("blur: the blur does not mix across a depth step or a crease", "[blur]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const int w = 48;
    const int h = 24;
    const Guide step = make_guide(w, h, [](int x, int) -> std::pair<float, glm::vec3> {
        return {x < 24 ? 2.0f : 2.5f, {0, 0, 1}};
    });
    // Same depth on both sides of the crease, normals at right angles.
    const Guide crease = make_guide(w, h, [](int x, int) -> std::pair<float, glm::vec3> {
        return {2.0f, x < 24 ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0)};
    });
    std::vector<float> halves(std::size_t(w) * std::size_t(h));
    for (std::size_t i = 0; i < halves.size(); ++i)
        halves[i] = int(i % std::size_t(w)) < 24 ? 0.2f : 0.9f;

    CHECK(max_difference(run_blur(loader, step, halves), halves) <= 1e-6f);
    CHECK(max_difference(run_blur(loader, crease, halves), halves) <= 1e-6f);
    // Control: with tolerances that accept everything the same inputs do blur,
    // so the two checks above can fail.
    BilateralBlurParameters accepting;
    accepting.depth_tolerance = 1000.0f;
    accepting.plane_tolerance = 1000.0f;
    accepting.normal_power = 1e-6f;
    CHECK(max_difference(run_blur(loader, step, halves, accepting), halves) > 0.05f);
}

// Output of a unit impulse on a flat camera-facing plane, against the
// codegen library's kernel: w[dx] * w[dy], summing to 1.
void check_impulse_response(const ShaderLoader& loader, const spiral::codegen::BlurKernel& kernel) {
    const int size = 4 * kernel.radius + 9;
    const int centre = size / 2;
    const Guide plane = make_guide(size, size, [](int, int) -> std::pair<float, glm::vec3> {
        return {3.0f, {0, 0, 1}};
    });
    std::vector<float> impulse(std::size_t(size) * std::size_t(size), 0.0f);
    impulse[std::size_t(centre) * std::size_t(size) + std::size_t(centre)] = 1.0f;
    const std::vector<float> response = run_blur(loader, plane, impulse);
    float worst = 0.0f;
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const int dx = x - centre;
            const int dy = y - centre;
            const bool inside = std::abs(dx) <= kernel.radius && std::abs(dy) <= kernel.radius;
            const float expected = inside ? kernel.weights[std::size_t(dx + kernel.radius)] *
                                                kernel.weights[std::size_t(dy + kernel.radius)]
                                          : 0.0f;
            worst = std::max(
                worst,
                std::abs(response[std::size_t(y) * std::size_t(size) + std::size_t(x)] - expected));
        }
    }
    const double total = std::accumulate(response.begin(), response.end(), 0.0);
    INFO("radius " << kernel.radius << ", sigma " << kernel.sigma);
    CHECK(worst <= 1e-6f);
    CHECK(std::abs(total - 1.0) <= 1e-5);
}

TEST_CASE("blur: on a flat plane the blur's weights are the generated kernel and sum to 1",
          "[blur]") {
    HeadlessContext context;
    const std::string build_sigma = SAO_TEST_BLUR_SIGMA;
    check_impulse_response(
        ShaderLoader::from_build_configuration(),
        spiral::codegen::gaussian_kernel(
            SAO_TEST_BLUR_RADIUS,
            build_sigma.empty() ? std::nullopt : std::optional(std::stod(build_sigma))));
    TemporaryFolder headers;
    write_blur_header(headers.path(), 3, 1.1);
    check_impulse_response(loader_with_override(headers.path()),
                           spiral::codegen::gaussian_kernel(3, 1.1));
}

TEST_CASE("blur: a 1-tap kernel is the identity", "[blur]") {
    HeadlessContext context;
    TemporaryFolder headers;
    write_blur_header(headers.path(), 0);
    const Guide guide = patchwork(37, 23);
    const std::vector<float> input = random_values(37 * 23, 7);
    CHECK(run_blur(loader_with_override(headers.path()), guide, input) == input);
}

TEST_CASE("blur: sky passes through and never leaks into surfaces", "[blur]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Guide guide = patchwork(64, 40);
    std::vector<float> input = random_values(64 * 40, 11);
    for (std::size_t i = 0; i < input.size(); ++i) {
        if (guide.depth[i] == 0.0f) input[i] = 50.0f;  // far outside the surfaces' range
    }
    const std::vector<float> output = run_blur(loader, guide, input);
    int sky = 0;
    for (std::size_t i = 0; i < input.size(); ++i) {
        if (guide.depth[i] == 0.0f) {
            ++sky;
            CHECK(output[i] == input[i]);
        } else {
            CHECK(output[i] <= 1.0f);
        }
    }
    CHECK(sky > 100);
}

}  // namespace
}  // namespace deepgi::test

namespace deepgi::test {
namespace {

TEST_CASE("blur: on rough guides the blur equals a CPU evaluation of its formula", "[blur]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Guide guide = rough_patchwork(61, 43);
    const std::vector<Signal> input = {Signal{1, random_values(61 * 43, 3)}};
    const std::vector<Signal> expected = cpu_blur(guide, input, build_kernel());
    const std::vector<float> gpu = run_blur(loader, guide, input.front().values);
    // Control: the blur changed the image, so agreement is not the identity.
    CHECK(max_difference(expected.front().values, input.front().values) > 0.1f);
    CHECK(max_difference(gpu, expected.front().values) <= 1e-4f);

    // The same with the tolerances and power moved, through a 7-tap kernel.
    TemporaryFolder headers;
    write_blur_header(headers.path(), 3, 1.1);
    BilateralBlurParameters loose;
    loose.depth_tolerance = 0.3f;
    loose.normal_power = 2.5f;
    loose.plane_tolerance = 0.05f;
    const std::vector<float> gpu_loose =
        run_blur(loader_with_override(headers.path()), guide, input.front().values, loose);
    CHECK(max_difference(gpu_loose,
                         cpu_blur(guide, input, spiral::codegen::gaussian_kernel(3, 1.1), loose)
                             .front()
                             .values) <= 1e-4f);
}

TEST_CASE("blur: taps weigh (1 - d^2 / e^2) by their distance in metres, none past the extent",
          "[blur]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Guide guide = rough_patchwork(61, 43);
    const std::vector<Signal> input = {Signal{1, random_values(61 * 43, 3)}};
    const std::vector<float> unlimited = run_blur(loader, guide, input.front().values);

    SECTION("an extent within the kernel's reach equals the CPU evaluation") {
        // Neighbouring pixels lie 0.023 to 0.09 m apart on these tiles
        // (depth 1 to 3.8), so 0.08 m cuts the kernel short on most of them.
        const float extent = 0.08f;
        const std::vector<float> gpu = run_blur(loader, guide, input.front().values, {}, extent);
        const std::vector<Signal> expected =
            cpu_blur(guide, input, build_kernel(), {}, double(extent));
        CHECK(max_difference(gpu, expected.front().values) <= 1e-4f);
        // Control: the extent changed the result.
        CHECK(max_difference(gpu, unlimited) > 0.05f);
    }
    SECTION("an extent shorter than the pixel spacing leaves every pixel as it was") {
        const std::vector<float> gpu = run_blur(loader, guide, input.front().values, {}, 0.01f);
        CHECK(max_difference(gpu, input.front().values) <= 1e-6f);
    }
    SECTION("an extent far beyond the kernel's reach is no limit") {
        const std::vector<float> gpu = run_blur(loader, guide, input.front().values, {}, 1e4f);
        CHECK(max_difference(gpu, unlimited) <= 1e-6f);
    }
}

TEST_CASE("blur: two sources blurred together get the weights each gets alone", "[blur]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Guide guide = rough_patchwork(53, 37);
    // AO-like one-channel source and radiosity-like RGBA source (E + confidence).
    const Signal ao{1, random_values(53 * 37, 5)};
    Signal radiosity{4, random_values(53 * 37 * 4, 9)};
    for (float& value : radiosity.values) value *= 20.0f;
    const std::vector<Signal> together = run_blur_sources(loader, guide, {ao, radiosity});
    REQUIRE(together.size() == 2);
    const std::vector<Signal> expected = cpu_blur(guide, {ao, radiosity}, build_kernel());
    CHECK(max_difference(together[0].values, expected[0].values) <= 1e-4f);
    CHECK(max_difference(together[1].values, expected[1].values) <= 20.0f * 1e-4f);
    // Alone, each source gives the same result as in the pair.
    CHECK(max_difference(run_blur_sources(loader, guide, {ao}).front().values,
                         together[0].values) <= 1e-6f);
    CHECK(max_difference(run_blur_sources(loader, guide, {radiosity}).front().values,
                         together[1].values) <= 20.0f * 1e-6f);
}

TEST_CASE(
    "blur: the second source reaches max(extent, start / n) after n frames, the first the "
    "extent",
    "[blur]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Guide guide = rough_patchwork(61, 43);
    const Signal ao{1, random_values(61 * 43, 3)};
    const Signal e{1, random_values(61 * 43, 8)};
    // Neighbours lie 0.023 to 0.09 m apart (the test above): 0.03 m keeps
    // few taps, 0.08 m most.
    const float extent = 0.03f;
    auto alone = [&](const Signal& source, float reach) {
        return run_blur_sources(loader, guide, {source}, {}, reach).front().values;
    };
    const std::vector<float> narrow = alone(e, extent);
    const std::vector<float> wide = alone(e, 0.08f);
    REQUIRE(max_difference(narrow, wide) > 0.05f);  // the two reaches differ here
    auto check = [&](const SecondReach& second, const std::vector<float>& expected) {
        const std::vector<Signal> out =
            run_blur_sources(loader, guide, {ao, e}, {}, extent, second);
        CHECK(max_difference(out[0].values, alone(ao, extent)) <= 1e-6f);
        CHECK(max_difference(out[1].values, expected) <= 1e-5f);
    };
    SECTION("on the first frame, start") {
        check({.start = 0.08f}, wide);
    }
    SECTION("0.32 / 4 = 0.08 after 4 frames") {
        check({.start = 0.32f, .temporal_frame = 3}, wide);
    }
    SECTION("never below the extent: 0.32 / 100 after 100 frames") {
        check({.start = 0.32f, .temporal_frame = 99}, narrow);
    }
    SECTION("start 0: the extent") {
        check({}, narrow);
    }
}

TEST_CASE("blur: a blur of 0 or 3 sources, or with mismatched inputs, is refused", "[blur]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    CHECK_THROWS_AS(create_bilateral_blur(loader, 0), InputError);
    CHECK_THROWS_AS(create_bilateral_blur(loader, 3), InputError);
    BilateralBlur blur = create_bilateral_blur(loader, 2);
    const GLenum one_format[] = {GL_R16F};
    CHECK_THROWS_AS(resize_bilateral_blur(blur, 8, 8, one_format), InputError);
    const GLenum formats[] = {GL_R16F, GL_RGBA16F};
    resize_bilateral_blur(blur, 8, 8, formats);
    const GLuint one_source[] = {blur.key.get()};
    CHECK_THROWS_AS(run_bilateral_blur(blur, one_source, 0, 0, 0), InputError);
}

}  // namespace
}  // namespace deepgi::test
