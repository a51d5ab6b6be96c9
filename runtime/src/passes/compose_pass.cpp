// Layer-0 outgoing radiance: direct light, albedo times the blurred deep
// radiosity E (the environment filling where its confidence is low) times the
// blurred deep SAO visibility, and emissive (docs/design.md, section 5.11).
#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

namespace {

class ComposePass final : public Pass {
public:
    ComposePass(const ShaderLoader& loader, const Scene& scene)
        : scene_(&scene), program_(build_fullscreen_program(loader, "compose.frag")) {}

    std::string_view name() const override { return "compose"; }

    PassDeclaration declaration(const RenderSettings& settings) const override {
        PassDeclaration declaration = {
            .reads = {{DEEPGI_UNIT_DIRECT_LIGHT, "direct_light.radiance"},
                      {DEEPGI_UNIT_GBUFFER_ALBEDO, "gbuffer.albedo"},
                      {DEEPGI_UNIT_GBUFFER_EMISSIVE, "gbuffer.emissive"},
                      {DEEPGI_UNIT_GBUFFER_DEPTH, "gbuffer.depth"},
                      {DEEPGI_UNIT_AO, "ao.blurred"},
                      {DEEPGI_UNIT_GBUFFER_NORMAL, "gbuffer.normal"},
                      {DEEPGI_UNIT_RADIOSITY, "radiosity.blurred"}},
            .writes = {"compose.radiance"}};
        // Mirror pixels, when the reflection pass runs (compose.frag's unit 3).
        if (reflections_traced(*scene_, settings))
            declaration.reads.push_back({3, "reflection.radiance"});
        return declaration;
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        radiance_ = gl::create_texture_2d(GL_R11F_G11F_B10F, width_, height_);
        label_texture(radiance_, name(), "radiance");
        framebuffer_ = framebuffer_for(radiance_, "compose");
    }

    void run(FrameResources& frame) override {
        begin_fullscreen(framebuffer_.get(), width_, height_);
        const RenderSettings& settings = *frame.settings;
        glProgramUniform3i(program_.get(), DEEPGI_UNIFORM_COMPOSE_TERMS,
                           settings.ao.enabled ? 1 : 0, settings.radiosity.enabled ? 1 : 0,
                           settings.environment ? 1 : 0);
        glProgramUniform1i(program_.get(), DEEPGI_UNIFORM_COMPOSE_REFLECTIONS,
                           reflections_traced(*scene_, settings) ? 1 : 0);
        glUseProgram(program_.get());
        draw_fullscreen_triangle(frame.empty_vertex_array);
        frame.publish("compose.radiance", radiance_.get());
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        return {{.name = "compose-radiance",
                 .texture = radiance_.get(),
                 .width = width_,
                 .height = height_}};
    }

private:
    const Scene* scene_;  // the renderer's own copy, which outlives its passes
    gl::Program program_;
    gl::Texture radiance_;  // R11F_G11F_B10F
    gl::Framebuffer framebuffer_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_compose_pass(const ShaderLoader& loader, const Scene& scene) {
    return std::make_unique<ComposePass>(loader, scene);
}

}  // namespace deepgi
