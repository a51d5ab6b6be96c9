// Layer-0 outgoing radiance: direct light, albedo times the blurred deep
// radiosity E (the environment filling where its confidence is low) times the
// blurred deep SAO visibility, and emissive (docs/design.md, section 5.11).
#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

namespace {

// Texture bindings of compose.frag.
constexpr GLuint normal_binding = 0;
constexpr GLuint albedo_binding = 1;
constexpr GLuint emissive_binding = 2;
constexpr GLuint depth_binding = 4;
constexpr GLuint direct_light_binding = 7;
constexpr GLuint ao_binding = 11;
constexpr GLuint radiosity_binding = 14;
constexpr GLuint reflection_binding = 3;  // mirror pixels' reflected radiance

class ComposePass final : public Pass {
public:
    ComposePass(const ShaderLoader& loader, const Scene& scene)
        : scene_(&scene), program_(build_fullscreen_program(loader, "compose.frag")) {}

    std::string_view name() const override { return "compose"; }

    PassDeclaration declaration(const RenderSettings& settings) const override {
        PassDeclaration declaration = {.reads = {{direct_light_binding, "direct_light.radiance"},
                                                 {albedo_binding, "gbuffer.albedo"},
                                                 {emissive_binding, "gbuffer.emissive"},
                                                 {depth_binding, "gbuffer.depth"},
                                                 {ao_binding, "ao.blurred"},
                                                 {normal_binding, "gbuffer.normal"},
                                                 {radiosity_binding, "radiosity.blurred"}},
                                       .writes = {"compose.radiance"},
                                       // Which materials are mirrors (reflections_traced).
                                       .value_reads = {"gbuffer.mirror_roughness"}};
        // Mirror pixels, when the reflection pass runs.
        if (reflections_traced(*scene_, settings))
            declaration.reads.push_back({reflection_binding, "reflection.filtered"});
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
        // Which terms it adds is the frame's: FrameConstants' ao_term,
        // radiosity_term, environment_term and reflection_term.
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
