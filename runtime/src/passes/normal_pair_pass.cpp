// Both G-buffer layers' encoded normals in one RGBA16F texture (layer 0 in RG,
// layer 1 in BA; normal_pair.frag), for the SAO estimators that read a
// stored surface's normal at each tap or step (ao_method_reads_normal_pair:
// the march, the default, the thick spiral and the solid angle): they then
// read both layers' normals with one fetch (docs/ao-accuracy.md, "The march
// reads the pair too").
#include "passes/passes.hpp"

#include <fmt/format.h>

namespace deepgi {

namespace {

// Texture binding of normal_pair.frag.
constexpr GLuint normal_binding = 0;

class NormalPairPass final : public Pass {
public:
    explicit NormalPairPass(const ShaderLoader& loader)
        : program_(build_fullscreen_program(loader, "normal_pair.frag")) {}

    std::string_view name() const override { return "normal_pair"; }

    // No other estimator reads it.
    bool enabled(const RenderSettings& settings) const override {
        return ao_method_reads_normal_pair(settings.ao.method);
    }

    PassDeclaration declaration(const RenderSettings&) const override {
        return {.reads = {{normal_binding, "gbuffer.normal"}}, .writes = {"normal_pair"}};
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        pair_ = gl::create_texture_2d(GL_RGBA16F, width_, height_);
        label_texture(pair_, name(), "both layers' encoded normals");
        framebuffer_ = framebuffer_for(pair_, "normal pair");
    }

    void run(FrameResources& frame) override {
        begin_fullscreen(framebuffer_.get(), width_, height_);
        glUseProgram(program_.get());
        draw_fullscreen_triangle(frame.empty_vertex_array);
        frame.publish("normal_pair", pair_.get());
    }

    // The encoded normals (octahedral x, y) as stored, one file per layer.
    std::vector<PassOutput> outputs(const FrameResources&) const override {
        std::vector<PassOutput> list;
        for (int layer = 0; layer < 2; ++layer)
            list.push_back({.name = fmt::format("normal_pair-layer{}", layer),
                            .texture = pair_.get(),
                            .width = width_,
                            .height = height_,
                            .decode = layer == 0 ? OutputDecode::floats_rg_as_rgb
                                                 : OutputDecode::floats_ba_as_rgb});
        return list;
    }

private:
    gl::Program program_;
    gl::Texture pair_;
    gl::Framebuffer framebuffer_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_normal_pair_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<NormalPairPass>(loader);
}

}  // namespace deepgi
