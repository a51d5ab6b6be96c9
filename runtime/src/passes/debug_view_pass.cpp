// One intermediate texture shown instead of the final image, written into the
// display image so the window and --output have one image either way.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

namespace {

// Texture bindings of debug_view.frag.
constexpr GLuint normal_binding = 0;
constexpr GLuint albedo_binding = 1;
constexpr GLuint emissive_binding = 2;
constexpr GLuint motion_binding = 3;
constexpr GLuint depth_binding = 4;
constexpr GLuint direct_light_binding = 7;
constexpr GLuint ao_blurred_binding = 11;
constexpr GLuint ao_raw_binding = 13;
constexpr GLuint radiosity_blurred_binding = 14;
constexpr GLuint irradiance_layer0_binding = 17;
constexpr GLuint irradiance_layer1_binding = 18;
constexpr GLuint prepared_radiance_binding = 21;
constexpr GLuint ao_temporal_binding = 28;
constexpr GLuint reflection_hit_binding = 5;
constexpr GLuint statistics_binding = 9;

class DebugViewPass final : public Pass {
public:
    DebugViewPass(const ShaderLoader& loader, const Scene& scene)
        : scene_(&scene), program_(build_fullscreen_program(loader, "debug_view.frag")) {}

    std::string_view name() const override { return "debug_view"; }

    PassDeclaration declaration(const RenderSettings& settings) const override {
        std::vector<PassRead> reads = {{normal_binding, "gbuffer.normal"},
                                       {albedo_binding, "gbuffer.albedo"},
                                       {emissive_binding, "gbuffer.emissive"},
                                       {motion_binding, "gbuffer.motion"},
                                       {depth_binding, "gbuffer.depth"},
                                       {direct_light_binding, "direct_light.radiance"},
                                       {ao_raw_binding, "ao.raw"},
                                       {ao_blurred_binding, "ao.blurred"},
                                       {ao_temporal_binding, "ao.temporal"},
                                       {prepared_radiance_binding, "radiosity_prepare.radiance"},
                                       {radiosity_blurred_binding, "radiosity.blurred"},
                                       {irradiance_layer0_binding, "radiosity.irradiance.layer0"},
                                       {irradiance_layer1_binding, "radiosity.irradiance.layer1"},
                                       {statistics_binding, "frame_statistics"}};
        // The hit layer of each mirror ray. The declaration is made before any
        // value exists, so it asks the settings, as compose does.
        if (reflections_traced(*scene_, settings))
            reads.push_back({reflection_hit_binding, "reflection.hit"});
        // Which materials are mirrors (reflections_traced).
        return {
            .reads = std::move(reads), .writes = {}, .value_reads = {"gbuffer.mirror_roughness"}};
    }
    void resize(FrameResources&) override {}
    bool enabled(const RenderSettings& settings) const override {
        return settings.view != DebugView::final_image;
    }

    void run(FrameResources& frame) override {
        // Whether the reflection pass ran is the frame's decision
        // (FrameConstants.reflection_term), which the shader reads as compose does.
        draw_into_display(frame, program_);
    }

    std::vector<PassOutput> outputs(const FrameResources& frame) const override {
        return {display_output(frame, "debug_view-colour")};
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
