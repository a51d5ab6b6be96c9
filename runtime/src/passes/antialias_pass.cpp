// Anti-aliasing after the tonemap: the displayed image is copied aside and
// filtered back into the display (shaders/antialias.frag). It runs on the
// final image only and reads no pass output, so every dumped pass output
// the tests read (AO, irradiance) is the same with it on or off.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

Antialias create_antialias(const ShaderLoader& loader) {
    Antialias antialias;
    antialias.program = build_fullscreen_program(loader, "antialias.frag");
    return antialias;
}

void run_antialias(Antialias& antialias, GLuint source, GLuint target_framebuffer, int width,
                   int height, GLuint empty_vertex_array) {
    begin_fullscreen(target_framebuffer, width, height);
    glUseProgram(antialias.program.get());
    // Binding 0: antialias.frag's local binding of the tonemapped image.
    glBindTextureUnit(0, source);
    antialias.block.bind(antialias.parameters);
    draw_fullscreen_triangle(empty_vertex_array);
}

namespace {

class AntialiasPass final : public Pass {
public:
    explicit AntialiasPass(const ShaderLoader& loader) : antialias_(create_antialias(loader)) {}

    std::string_view name() const override { return "antialias"; }

    PassDeclaration declaration(const RenderSettings&) const override {
        // Reads and writes only the display image, which is not a named output.
        return {.reads = {}, .writes = {}};
    }
    void resize(FrameResources& frame) override {
        width_ = frame.settings->width;
        height_ = frame.settings->height;
        copy_ = gl::create_texture_2d(GL_RGBA8, width_, height_);
        glObjectLabel(GL_TEXTURE, copy_.get(), -1, "antialias.tonemapped");
    }
    bool enabled(const RenderSettings& settings) const override {
        return settings.view == DebugView::final_image && settings.antialias != 0;
    }

    void run(FrameResources& frame) override {
        glCopyImageSubData(frame.display.get(), GL_TEXTURE_2D, 0, 0, 0, 0, copy_.get(),
                           GL_TEXTURE_2D, 0, 0, 0, 0, width_, height_, 1);
        run_antialias(antialias_, copy_.get(), frame.display_framebuffer.get(), width_, height_,
                      frame.empty_vertex_array);
    }

    std::vector<PassOutput> outputs(const FrameResources& frame) const override {
        return {display_output(frame, "antialias-colour")};
    }

private:
    Antialias antialias_;
    gl::Texture copy_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_antialias_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<AntialiasPass>(loader);
}

}  // namespace deepgi
