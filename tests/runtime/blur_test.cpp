// The bilateral blur on hand-made guides, where the right answer is known
// without running a blur: constants stay constant, steps and creases stay
// sharp, a flat plane gives back the generated Gaussian.
#include "passes/passes.hpp"
#include "sao_test_support.hpp"
#include "shader_shared.hpp"

#include <catch2/catch.hpp>

#include <functional>
#include <numeric>

namespace deepgi::test {
namespace {

// What the blur reads besides its source: layer-0 depth and normal per pixel.
struct Guide {
    int width = 0;
    int height = 0;
    std::vector<float> depth;       // metres, 0 = no surface
    std::vector<glm::vec3> normal;  // camera space, unit
    float at_depth(int x, int y) const {
        return depth[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    }
};

Guide make_guide(int width, int height,
                 const std::function<std::pair<float, glm::vec3>(int, int)>& surface) {
    Guide guide;
    guide.width = width;
    guide.height = height;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            auto [depth, normal] = surface(x, y);
            guide.depth.push_back(depth);
            guide.normal.push_back(glm::normalize(normal));
        }
    }
    return guide;
}

// Octahedral encoding, as gbuffer_encoding.glsl stores normals.
glm::vec2 encode_octahedral(glm::vec3 n) {
    n /= std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    if (n.z >= 0.0f) return {n.x, n.y};
    return {(1.0f - std::abs(n.y)) * (n.x >= 0.0f ? 1.0f : -1.0f),
            (1.0f - std::abs(n.x)) * (n.y >= 0.0f ? 1.0f : -1.0f)};
}

// Runs the pass on `source` (one float per pixel) and returns the output.
std::vector<float> run_blur(const ShaderLoader& loader, const Guide& guide,
                            const std::vector<float>& source,
                            const BilateralBlurParameters& parameters = {}) {
    const int w = guide.width;
    const int h = guide.height;
    shader_shared::FrameConstants constants{};
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
    gl::Texture input = gl::create_texture_2d(GL_R32F, w, h);
    glTextureSubImage2D(input.get(), 0, 0, 0, w, h, GL_RED, GL_FLOAT, source.data());
    gl::VertexArray empty = gl::create_vertex_array();

    BilateralBlur blur = create_bilateral_blur(loader, parameters);
    resize_bilateral_blur(blur, w, h, GL_R32F);
    run_bilateral_blur(blur, input.get(), depth.get(), normal.get(), empty.get());
    std::vector<float> output(source.size());
    glGetTextureImage(blur.output.get(), 0, GL_RED, GL_FLOAT,
                      GLsizei(output.size() * sizeof(float)), output.data());
    return output;
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
