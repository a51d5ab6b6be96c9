// Mirror reflections through both deep G-buffer layers (reflection.frag,
// docs/reflections.md): one reflected ray per mirror pixel, marched in camera
// space against the layers and the solids behind them (backface_depth), with
// long steps over a nearest-depth pyramid this pass builds for itself. The
// pass runs only for scenes with a mirror material; compose reads its
// radiance on mirror pixels.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>

namespace deepgi {

bool reflections_traced(const Scene& scene, const RenderSettings& settings) {
    if (!settings.reflection.enabled) return false;
    return std::any_of(scene.materials.begin(), scene.materials.end(), [&](const Material& m) {
        return m.roughness <= settings.mirror_roughness && m.metallic >= 0.5f;
    });
}

namespace {

// Texture units of reflection.frag's samplers (local to this pass).
constexpr GLuint unit_normal = 0;
constexpr GLuint unit_albedo = 1;
constexpr GLuint unit_emissive = 2;
constexpr GLuint unit_irradiance_layer0 = 3;
constexpr GLuint unit_depth = 4;
constexpr GLuint unit_irradiance_layer1 = 5;
constexpr GLuint unit_direct = 6;
constexpr GLuint unit_backface = 7;
constexpr GLuint unit_nearest = 8;
constexpr GLuint image_finer = 0;  // NEAREST_REDUCE's source level

// Samples one long step may skip when the nearest-depth pyramid shows that
// none of them can be inside a layer.
constexpr int skip_steps = 8;

class ReflectionPass final : public Pass {
public:
    ReflectionPass(const ShaderLoader& loader, const Scene& scene)
        : scene_(&scene),
          march_(build_fullscreen_program(loader, "reflection.frag")),
          nearest_base_(
              build_fullscreen_program(loader, "reflection.frag", "#define NEAREST_BASE 1\n")),
          nearest_reduce_(
              build_fullscreen_program(loader, "reflection.frag", "#define NEAREST_REDUCE 1\n")) {}

    std::string_view name() const override { return "reflection"; }

    bool enabled(const RenderSettings& settings) const override {
        return reflections_traced(*scene_, settings);
    }

    PassDeclaration declaration(const RenderSettings& settings) const override {
        return {.reads = {{unit_normal, "gbuffer.normal"},
                          {unit_albedo, "gbuffer.albedo"},
                          {unit_emissive, "gbuffer.emissive"},
                          {unit_depth, "gbuffer.depth"},
                          {unit_direct, "direct_light.radiance"},
                          {unit_backface, "backface.depth"},
                          {unit_irradiance_layer0, "radiosity.irradiance.layer0"},
                          {unit_irradiance_layer1, "radiosity.irradiance.layer1"}},
                .writes = {"reflection.radiance", "reflection.hit"},
                // The solids behind open meshes are as thick as SAO's.
                .value_reads = {"sao.thickness", "gbuffer.mirror_roughness"},
                .value_writes = {{"reflection.layers", float(settings.reflection.layers)}}};
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        guard_ = frame.layout.guard;
        radiance_ = gl::create_texture_2d(GL_RGBA16F, width_, height_);
        hit_ = gl::create_texture_2d(GL_RGBA32F, width_, height_);
        label_texture(radiance_, name(), "radiance");
        label_texture(hit_, name(), "hit");
        framebuffer_ = gl::create_framebuffer();
        glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0, radiance_.get(), 0);
        glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT1, hit_.get(), 0);
        const GLenum outputs[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glNamedFramebufferDrawBuffers(framebuffer_.get(), 2, outputs);
        gl::check_framebuffer(framebuffer_, "reflection");

        levels_ = std::bit_width(unsigned(std::max(width_, height_)));  // floor(log2) + 1
        nearest_ = gl::create_texture(GL_TEXTURE_2D);
        glTextureStorage2D(nearest_.get(), levels_, GL_R32F, width_, height_);
        glTextureParameteri(nearest_.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
        glTextureParameteri(nearest_.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        label_texture(nearest_, name(), "nearest depth");
        level_framebuffers_.clear();
        for (int level = 0; level < levels_; ++level) {
            gl::Framebuffer framebuffer = gl::create_framebuffer();
            glNamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT0, nearest_.get(),
                                      level);
            gl::check_framebuffer(framebuffer, "reflection nearest depth");
            level_framebuffers_.push_back(std::move(framebuffer));
        }
    }

    void run(FrameResources& frame) override {
        const RenderSettings& settings = *frame.settings;
        const Scene& scene = *frame.scene;
        const float bounding_radius = 0.5f * glm::length(scene.bounds.max - scene.bounds.min);
        block_.bind({.distance = reflection_distance(settings, bounding_radius),
                     .steps = settings.reflection.steps,
                     .layers = settings.reflection.layers,
                     .thickness = frame.value("sao.thickness"),
                     .max_level = levels_ - 1,
                     .skip_steps = skip_steps,
                     .unused0 = 0,
                     .unused1 = 0,
                     .edge_fade_pixels = std::max(4.0f, 0.5f * float(guard_)),
                     .facing_fade_start = 0.2f,
                     .facing_fade_end = 0.5f,
                     .unused2 = 0.0f});

        // The nearest-depth pyramid: level 0 from layer 0, then each level
        // the minimum of the finer one (read as an image, written as a target).
        glUseProgram(nearest_base_.get());
        begin_fullscreen(level_framebuffers_[0].get(), width_, height_);
        draw_fullscreen_triangle(frame.empty_vertex_array);
        glUseProgram(nearest_reduce_.get());
        for (int level = 1; level < levels_; ++level) {
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
            glBindImageTexture(image_finer, nearest_.get(), level - 1, GL_FALSE, 0, GL_READ_ONLY,
                               GL_R32F);
            begin_fullscreen(level_framebuffers_[std::size_t(level)].get(),
                             std::max(width_ >> level, 1), std::max(height_ >> level, 1));
            draw_fullscreen_triangle(frame.empty_vertex_array);
        }
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);

        glUseProgram(march_.get());
        glBindTextureUnit(unit_nearest, nearest_.get());
        begin_fullscreen(framebuffer_.get(), width_, height_);
        draw_fullscreen_triangle(frame.empty_vertex_array);
        frame.publish("reflection.radiance", radiance_.get());
        frame.publish("reflection.hit", hit_.get());
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        auto output = [&](const char* name, const gl::Texture& texture, int channels,
                          OutputDecode decode) {
            return PassOutput{.name = name,
                              .texture = texture.get(),
                              .width = width_,
                              .height = height_,
                              .channels = channels,
                              .decode = decode};
        };
        std::vector<PassOutput> list = {
            output("reflection-radiance", radiance_, 3, OutputDecode::floats),
            output("reflection-weight", radiance_, 1, OutputDecode::alpha),
            output("reflection-hit", hit_, 3, OutputDecode::floats),
            output("reflection-jitter", hit_, 1, OutputDecode::alpha)};
        for (int level = 0; level < levels_; ++level)
            list.push_back({.name = fmt::format("reflection-nearest-level{}", level),
                            .texture = nearest_.get(),
                            .level = level,
                            .width = std::max(width_ >> level, 1),
                            .height = std::max(height_ >> level, 1),
                            .channels = 1});
        return list;
    }

private:
    const Scene* scene_;  // the renderer's own copy, which outlives its passes
    gl::Program march_;
    gl::Program nearest_base_;
    gl::Program nearest_reduce_;
    ParameterBlock<shader_shared::ReflectionParameters> block_;
    gl::Texture radiance_;  // RGBA16F: reflected radiance, hit weight
    gl::Texture hit_;       // RGBA32F: hit texel centre, layer, jitter
    gl::Framebuffer framebuffer_;
    gl::Texture nearest_;  // R32F with MIPs: nearest layer-0 linear depth
    std::vector<gl::Framebuffer> level_framebuffers_;
    int width_ = 0;
    int height_ = 0;
    int guard_ = 0;
    int levels_ = 1;
};

}  // namespace

std::unique_ptr<Pass> make_reflection_pass(const ShaderLoader& loader, const Scene& scene) {
    return std::make_unique<ReflectionPass>(loader, scene);
}

}  // namespace deepgi
