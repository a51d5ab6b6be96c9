// Filmic curve and sRGB encoding into the display image, guard band cropped.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

namespace {

// Texture binding of tonemap.frag.
constexpr GLuint radiance_binding = 8;
constexpr GLuint statistics_binding = 9;

class TonemapPass final : public Pass {
public:
    explicit TonemapPass(const ShaderLoader& loader)
        : program_(build_fullscreen_program(loader, "tonemap.frag")) {}

    std::string_view name() const override { return "tonemap"; }

    PassDeclaration declaration(const RenderSettings&) const override {
        return {.reads = {{radiance_binding, "compose.radiance"},
                          {statistics_binding, "frame_statistics"}},
                .writes = {}};
    }
    void resize(FrameResources&) override {}  // writes the frame's display image
    bool enabled(const RenderSettings& settings) const override {
        return settings.view == DebugView::final_image;
    }

    void run(FrameResources& frame) override { draw_into_display(frame, program_); }

    std::vector<PassOutput> outputs(const FrameResources& frame) const override {
        return {display_output(frame, "tonemap-colour")};
    }

private:
    gl::Program program_;
};

}  // namespace

std::unique_ptr<Pass> make_tonemap_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<TonemapPass>(loader);
}

}  // namespace deepgi
