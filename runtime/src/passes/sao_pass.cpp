// Deep SAO (docs/design.md, section 5.6). The tap pattern is whatever ao_taps.glsl the
// shader loader finds: the build's generated header in the renderer, a header
// written at run time by the noise study and the tests.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

namespace {

// Texture bindings of sao.frag.
constexpr GLuint normal_binding = 0;
constexpr GLuint depth_binding = 10;
constexpr GLuint backface_binding = 29;

class SaoPass final : public Pass {
public:
    explicit SaoPass(const ShaderLoader& loader)
        : one_layer_(build_fullscreen_program(loader, "sao.frag", "#define AO_LAYERS 1\n")),
          two_layers_(build_fullscreen_program(loader, "sao.frag", "#define AO_LAYERS 2\n")),
          // The thickness-aware spiral has its own include (ao_spiral_thick.glsl),
          // compiled in only where it runs.
          thick_one_layer_(build_fullscreen_program(
              loader, "sao.frag", "#define AO_LAYERS 1\n#define AO_SPIRAL_THICK 1\n")),
          thick_two_layers_(build_fullscreen_program(
              loader, "sao.frag", "#define AO_LAYERS 2\n#define AO_SPIRAL_THICK 1\n")) {}

    std::string_view name() const override { return "sao"; }

    PassDeclaration declaration(const RenderSettings& settings) const override {
        std::vector<PassRead> reads = {{depth_binding, "depth_pyramid"},
                                       {normal_binding, "gbuffer.normal"}};
        // Only the march and the thick spiral end each solid at its back face.
        if (ao_method_reads_back_faces(settings.ao.method))
            reads.push_back({backface_binding, "backface.depth"});
        return {.reads = std::move(reads), .writes = {"ao.raw"}};
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        // A float format: the solid-angle visibility is signed until compose
        // clamps it (sao.frag); a UNORM target would clamp it here.
        visibility_ = gl::create_texture_2d(GL_R16F, width_, height_);
        label_texture(visibility_, name(), "visibility");
        framebuffer_ = framebuffer_for(visibility_, "sao");
    }

    void run(FrameResources& frame) override {
        const AoSettings& settings = frame.settings->ao;
        const bool thick = settings.method == AoMethod::spiral_thick;
        const GLuint program = settings.layers == 1
                                   ? (thick ? thick_one_layer_ : one_layer_).get()
                                   : (thick ? thick_two_layers_ : two_layers_).get();
        begin_fullscreen(framebuffer_.get(), width_, height_);
        parameters_.bind({.radius = settings.radius,
                          .bias = settings.bias,
                          .intensity = settings.intensity,
                          .q = settings.q,
                          .max_mip = frame.integer("depth_pyramid.max_level"),
                          .method = static_cast<int>(settings.method),
                          .thickness = settings.thickness,
                          .unused0 = 0.0f});
        glUseProgram(program);
        draw_fullscreen_triangle(frame.empty_vertex_array);
        frame.publish("ao.raw", visibility_.get());
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        return {{.name = "ao-raw",
                 .texture = visibility_.get(),
                 .width = width_,
                 .height = height_,
                 .channels = 1}};
    }

private:
    gl::Program one_layer_;
    gl::Program two_layers_;
    gl::Program thick_one_layer_;
    gl::Program thick_two_layers_;
    ParameterBlock<shader_shared::SaoParameters> parameters_;
    gl::Texture visibility_;  // R16F ambient visibility, signed (at most 1)
    gl::Framebuffer framebuffer_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_sao_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<SaoPass>(loader);
}

}  // namespace deepgi
