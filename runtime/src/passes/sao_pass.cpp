// Deep SAO (docs/design.md, section 5.6). The tap pattern is whatever ao_taps.glsl the
// shader loader finds: the build's generated header in the renderer, a header
// written at run time by the noise study and the tests. Each estimator is an
// include of sao.frag chosen by `#define AO_METHOD` (ao_published.glsl,
// ao_solid_angle.glsl, ao_march.glsl, ao_spiral_thick.glsl, ao_gtao.glsl,
// ao_bitmask.glsl): one program per
// estimator and layer count (sao_program_table), picked by the settings.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace deepgi {

namespace {

// Texture bindings of sao.frag.
constexpr GLuint normal_binding = 0;
constexpr GLuint depth_binding = 10;
constexpr GLuint normal_pair_binding = 11;

// The define that builds one estimator: its include (sao.frag) and layers.
std::string program_defines(const SaoProgram& program) {
    return fmt::format("#define AO_LAYERS {}\n#define AO_METHOD {}\n", program.layers,
                       static_cast<int>(program.method));
}

class SaoPass final : public Pass {
public:
    // Every program the settings may ask for, built now: a setting never
    // compiles a shader later.
    explicit SaoPass(const ShaderLoader& loader) {
        for (const SaoProgram& program : sao_program_table())
            programs_.push_back(
                build_fullscreen_program(loader, "sao.frag", program_defines(program)));
    }

    std::string_view name() const override { return "sao"; }

    PassDeclaration declaration(const RenderSettings& settings) const override {
        std::vector<PassRead> reads = {{depth_binding, "depth_pyramid"},
                                       {normal_binding, "gbuffer.normal"}};
        // The estimators that read a stored surface's normal at each tap or
        // step take both layers' at once from the normal pair pass
        // (normal_pair.frag); the march and the thick spiral read the back
        // faces that end their solids from the pyramid (depth_pyramid.comp).
        if (ao_method_reads_normal_pair(settings.ao.method))
            reads.push_back({normal_pair_binding, "normal_pair"});
        const AoSettings& ao = settings.ao;
        return {.reads = std::move(reads),
                .writes = {"ao.raw"},
                // The level a tap reads is the pyramid's to say.
                .value_reads = {"depth_pyramid.q"},
                // The blur's reach is a fraction of the radius; the
                // reflections' solids are as thick as SAO's; the back faces
                // are rendered for as many layers as SAO tests.
                .value_writes = {{"sao.radius", ao.radius},
                                 {"sao.thickness", ao.thickness},
                                 {"sao.layers", float(ao.layers)}}};
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        // A float format: the solid-angle visibility is signed until compose
        // clamps it (ao_solid_angle.glsl); a UNORM target would clamp it here.
        visibility_ = gl::create_texture_2d(GL_R16F, width_, height_);
        label_texture(visibility_, name(), "visibility");
        framebuffer_ = framebuffer_for(visibility_, "sao");
    }

    void run(FrameResources& frame) override {
        const AoSettings& settings = frame.settings->ao;
        const std::vector<SaoProgram> table = sao_program_table();
        const auto chosen = std::find_if(table.begin(), table.end(), [&](const SaoProgram& p) {
            return p.method == settings.method && p.layers == settings.layers;
        });
        // validate() has checked the method and the layers against the same tables.
        const GLuint program = programs_.at(std::size_t(chosen - table.begin())).get();
        begin_fullscreen(framebuffer_.get(), width_, height_);
        parameters_.bind({.radius = settings.radius,
                          .bias = settings.bias,
                          .intensity = settings.intensity,
                          .q = frame.value("depth_pyramid.q"),
                          .max_mip = frame.integer("depth_pyramid.max_level"),
                          .slices = settings.slices,
                          .thickness = settings.thickness,
                          .steps = settings.steps});
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
    std::vector<gl::Program> programs_;  // in the order of sao_program_table()
    ParameterBlock<shader_shared::SaoParameters> parameters_;
    gl::Texture visibility_;  // R16F ambient visibility, signed (at most 1)
    gl::Framebuffer framebuffer_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace

std::vector<SaoProgram> sao_program_table() {
    std::vector<SaoProgram> table;
    for (const auto& method : enum_names(AoMethod{}))
        for (int layers = 1; layers <= limits::max_ao_layers; ++layers)
            table.push_back({.method = method.value, .layers = layers});
    return table;
}

std::unique_ptr<Pass> make_sao_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<SaoPass>(loader);
}

}  // namespace deepgi
