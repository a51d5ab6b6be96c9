// Radiosity prepare (shaders/radiosity_prepare.comp): the outgoing radiance
// and the normal of both G-buffer layers as rotated-grid MIP levels, built
// like the depth pyramid and with as many levels, so that texel t of level m
// of these and of the depth pyramid describe the same level-0 pixel; with
// `radiosity-prefilter` a coarse texel's radiance is the mean over its block's
// pixels on that pixel's surface. The gather reads them instead of the
// G-buffer (docs/radiosity.md).
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>

namespace deepgi {

namespace {

constexpr int group_size = 8;  // local_size of radiosity_prepare.comp

// Bindings of radiosity_prepare.comp. The base level samples the G-buffer,
// the direct light and last frame's E with its keys; every level writes the
// two destination images, and the levels above the base read the level below
// through the source images.
constexpr GLuint normal_binding = 0;
constexpr GLuint albedo_binding = 1;
constexpr GLuint emissive_binding = 2;
constexpr GLuint motion_binding = 3;
constexpr GLuint depth_binding = 4;
constexpr GLuint direct_light_binding = 7;
constexpr GLuint depth_pyramid_binding = 5;  // the levels above the base: the sources' depths
constexpr GLuint previous_layer0_binding = 15;
constexpr GLuint previous_layer1_binding = 16;
constexpr GLuint history_key_layer0_binding = 19;
constexpr GLuint history_key_layer1_binding = 20;
constexpr GLuint radiance_source_image = 0;
constexpr GLuint radiance_destination_image = 1;
constexpr GLuint normal_source_image = 2;
constexpr GLuint normal_destination_image = 3;
constexpr GLint source_level_location = 0;  // the reduction's `source_level`

int level_extent(int extent, int level) {
    return std::max(1, extent >> level);
}

gl::Texture create_mip_array(GLenum format, int width, int height, int levels) {
    gl::Texture texture = gl::create_texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(texture.get(), levels, format, width, height, DEEPGI_LAYER_COUNT);
    glTextureParameteri(texture.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glTextureParameteri(texture.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

class RadiosityPreparePass final : public Pass {
public:
    explicit RadiosityPreparePass(const ShaderLoader& loader)
        : base_level_(loader.build_program({{GL_COMPUTE_SHADER, "radiosity_prepare.comp"}},
                                           "#define PREPARE_BASE_LEVEL 1\n")),
          reduce_(loader.build_program({{GL_COMPUTE_SHADER, "radiosity_prepare.comp"}})) {}

    std::string_view name() const override { return "radiosity_prepare"; }

    PassDeclaration declaration(const RenderSettings&) const override {
        return {.reads = {{normal_binding, "gbuffer.normal"},
                          {albedo_binding, "gbuffer.albedo"},
                          {emissive_binding, "gbuffer.emissive"},
                          {motion_binding, "gbuffer.motion"},
                          {depth_binding, "gbuffer.depth"},
                          {direct_light_binding, "direct_light.radiance"},
                          {depth_pyramid_binding, "depth_pyramid"}},
                .writes = {"radiosity_prepare.radiance", "radiosity_prepare.normal"}};
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        // As many levels as the depth pyramid, which resizes first and
        // publishes its deepest level.
        levels_ = frame.integer("depth_pyramid.max_level") + 1;
        radiance_ = create_mip_array(GL_RGBA16F, width_, height_, levels_);
        label_texture(radiance_, name(), "radiance");
        normal_ = create_mip_array(GL_RG16F, width_, height_, levels_);
        label_texture(normal_, name(), "normal");
    }

    void run(FrameResources& frame) override {
        const RadiositySettings& settings = frame.settings->radiosity;
        const GLuint base = base_level_.get();
        glUseProgram(base);
        parameters_.bind({.boost = settings.boost,
                          .rho_prop = settings.rho_prop,
                          .prefilter = settings.prefilter ? 1.0f : 0.0f,
                          .unused0 = 0.0f});
        // Last frame's filtered E and its keys (radiosity_pass.cpp owns them).
        glBindTextureUnit(previous_layer0_binding, frame.history("radiosity-layer0").previous());
        glBindTextureUnit(previous_layer1_binding, frame.history("radiosity-layer1").previous());
        glBindTextureUnit(history_key_layer0_binding,
                          frame.history("radiosity-key-layer0").previous());
        glBindTextureUnit(history_key_layer1_binding,
                          frame.history("radiosity-key-layer1").previous());
        bind_level(0, radiance_destination_image, normal_destination_image, GL_WRITE_ONLY);
        dispatch_over(width_, height_);

        glUseProgram(reduce_.get());
        for (int level = 1; level < levels_; ++level) {
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            bind_level(level - 1, radiance_source_image, normal_source_image, GL_READ_ONLY);
            bind_level(level, radiance_destination_image, normal_destination_image, GL_WRITE_ONLY);
            glUniform1i(source_level_location, level - 1);
            dispatch_over(level_extent(width_, level), level_extent(height_, level));
        }
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
        frame.publish("radiosity_prepare.radiance", radiance_.get());
        frame.publish("radiosity_prepare.normal", normal_.get());
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        std::vector<PassOutput> list;
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer) {
            for (int level = 0; level < levels_; ++level) {
                const int w = level_extent(width_, level);
                const int h = level_extent(height_, level);
                list.push_back({.name = fmt::format("radiosity_prepare-radiance-layer{}-level{}",
                                                    layer, level),
                                .texture = radiance_.get(),
                                .layer = layer,
                                .level = level,
                                .width = w,
                                .height = h});
                list.push_back(
                    {.name = fmt::format("radiosity_prepare-normal-layer{}-level{}", layer, level),
                     .texture = normal_.get(),
                     .layer = layer,
                     .level = level,
                     .width = w,
                     .height = h,
                     // The octahedral encoding as stored (x, y, 0).
                     .decode = OutputDecode::floats_rg_as_rgb});
            }
        }
        return list;
    }

private:
    void bind_level(int level, GLuint radiance_unit, GLuint normal_unit, GLenum access) const {
        glBindImageTexture(radiance_unit, radiance_.get(), level, GL_TRUE, 0, access, GL_RGBA16F);
        glBindImageTexture(normal_unit, normal_.get(), level, GL_TRUE, 0, access, GL_RG16F);
    }

    static void dispatch_over(int width, int height) {
        glDispatchCompute(GLuint((width + group_size - 1) / group_size),
                          GLuint((height + group_size - 1) / group_size), 1);
    }

    gl::Program base_level_;  // level 0 from the G-buffer, direct light and last frame's E
    gl::Program reduce_;      // level m + 1 from level m
    ParameterBlock<shader_shared::RadiosityPrepareParameters> parameters_;
    gl::Texture radiance_;  // RGBA16F array, 2 layers: rgb B, a 1 where a surface is
    gl::Texture normal_;    // RG16F array, 2 layers: octahedral camera-space normal
    int width_ = 0;
    int height_ = 0;
    int levels_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_radiosity_prepare_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<RadiosityPreparePass>(loader);
}

}  // namespace deepgi
