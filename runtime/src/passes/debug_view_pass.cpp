// One intermediate texture shown instead of the final image, written into the
// display image so the window and --output have one image either way.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

namespace {

class DebugViewPass final : public Pass {
public:
    DebugViewPass(const ShaderLoader& loader, const Scene& scene)
        : scene_(&scene), program_(build_fullscreen_program(loader, "debug_view.frag")) {}

    std::string_view name() const override { return "debug_view"; }

    PassDeclaration declaration(const RenderSettings& settings) const override {
        std::vector<PassRead> reads = gbuffer_and_direct_light_reads();
        reads.insert(reads.end(),
                     {{DEEPGI_UNIT_AO_RAW, "ao.raw"},
                      {DEEPGI_UNIT_AO, "ao.blurred"},
                      {DEEPGI_UNIT_AO_TEMPORAL, "ao.temporal"},
                      {DEEPGI_UNIT_RADIOSITY_RADIANCE, "radiosity_prepare.radiance"},
                      {DEEPGI_UNIT_RADIOSITY, "radiosity.blurred"},
                      // The temporally filtered E of each layer, at the units the
                      // radiosity pass uses for the raw gather.
                      {DEEPGI_UNIT_RADIOSITY_RAW_LAYER0, "radiosity.irradiance.layer0"},
                      {DEEPGI_UNIT_RADIOSITY_RAW_LAYER1, "radiosity.irradiance.layer1"}});
        // The hit layer of each mirror ray, at debug_view.frag's unit 5.
        if (reflections_traced(*scene_, settings)) reads.push_back({5, "reflection.hit"});
        return {.reads = std::move(reads), .writes = {}};
    }
    void resize(FrameResources&) override {}
    bool enabled(const RenderSettings& settings) const override {
        return settings.view != DebugView::final_image;
    }

    void run(FrameResources& frame) override {
        begin_fullscreen(frame.display_framebuffer.get(), frame.settings->width,
                         frame.settings->height);
        glProgramUniform1i(program_.get(), 1, reflections_traced(*scene_, *frame.settings) ? 1 : 0);
        glUseProgram(program_.get());
        draw_fullscreen_triangle(frame.empty_vertex_array);
    }

    std::vector<PassOutput> outputs(const FrameResources& frame) const override {
        return {{.name = "debug_view-colour",
                 .texture = frame.display.get(),
                 .width = frame.settings->width,
                 .height = frame.settings->height,
                 .decode = OutputDecode::unorm_rgb}};
    }

private:
    const Scene* scene_;  // the renderer's own copy, which outlives its passes
    gl::Program program_;
};

}  // namespace

std::unique_ptr<Pass> make_debug_view_pass(const ShaderLoader& loader, const Scene& scene) {
    return std::make_unique<DebugViewPass>(loader, scene);
}

}  // namespace deepgi
