// Separable bilateral blur (docs/design.md, section 5.10): a horizontal draw into an
// intermediate texture per source, then a vertical draw into the outputs. The
// kernel is the generated blur_kernel.glsl the shader loader finds.
//
// The frame's blur pass filters the AO visibility and layer 0's radiosity E
// (with its confidence) in the same draws: both are keyed on the same depth
// and normal, so each tap's weight is computed once for both.
#include "deepgi/errors.hpp"
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>

#include <cmath>

namespace deepgi {

namespace {

// Texture bindings of bilateral_blur_key.frag (normal, depth) and
// bilateral_blur.frag (the sources and the key).
constexpr GLuint normal_binding = 0;
constexpr GLuint depth_binding = 10;
constexpr GLuint source_bindings[max_blur_sources] = {12, 25};
constexpr GLuint key_binding = 26;
// ivec2 uniform: (1, 0) horizontal, (0, 1) vertical.
constexpr GLint direction_location = 23;

// E's reach on the first frame after history was invalidated, in radiosity
// radii, divided by the frames since and never below the AO's reach
// (docs/radiosity.md, "The blur"). At the auto lengths the AO's reach is
// 0.083 radiosity radii, which this meets at 48 frames, so a mean of 64
// frames or more, and the accuracy against the ray tracer, are blurred as
// before; at 16 frames E reaches 0.25 radii, where a still camera's E after
// 16 frames was closest to its converged image (cornell, 160x90).
constexpr float early_radiosity_reach = 4.0f;

void check_parameters(const BilateralBlurParameters& parameters) {
    auto positive = [](float value) { return std::isfinite(value) && value > 0.0f; };
    if (!positive(parameters.depth_tolerance) || !positive(parameters.normal_power) ||
        !positive(parameters.plane_tolerance)) {
        throw InputError("bilateral blur tolerances and normal power must be finite and > 0");
    }
}

gl::Framebuffer framebuffer_for_all(const gl::Texture* const* textures, int count,
                                    const char* what) {
    gl::Framebuffer framebuffer = gl::create_framebuffer();
    GLenum buffers[max_blur_sources] = {};
    for (int i = 0; i < count; ++i) {
        buffers[i] = GLenum(GL_COLOR_ATTACHMENT0 + i);
        glNamedFramebufferTexture(framebuffer.get(), buffers[i], textures[i]->get(), 0);
    }
    glNamedFramebufferDrawBuffers(framebuffer.get(), count, buffers);
    gl::check_framebuffer(framebuffer, what);
    return framebuffer;
}

// Smooths the raw deep SAO visibility (R16F) and layer 0's filtered radiosity
// E + confidence (RGBA16F) with one set of weights.
class BlurPass final : public Pass {
public:
    explicit BlurPass(const ShaderLoader& loader) : blur_(create_bilateral_blur(loader, 2)) {}

    std::string_view name() const override { return "blur"; }

    PassDeclaration declaration(const RenderSettings&) const override {
        // run_bilateral_blur() binds the sources and keys again itself, since
        // its horizontal step rebinds the source units to its intermediates.
        return {.reads = {{source_bindings[0], "ao.temporal"},
                          {source_bindings[1], "radiosity.irradiance.layer0"},
                          {depth_binding, "depth_pyramid"},
                          {normal_binding, "gbuffer.normal"}},
                .writes = {"ao.blurred", "radiosity.blurred"},
                .value_reads = {"sao.radius", "radiosity.radius"}};
    }

    void resize(FrameResources& frame) override {
        const GLenum formats[] = {GL_R16F, GL_RGBA16F};
        resize_bilateral_blur(blur_, frame.layout.internal_width, frame.layout.internal_height,
                              formats);
        label_texture(blur_.horizontal, name(), "ao horizontal");
        label_texture(blur_.output, name(), "ao output");
        label_texture(blur_.second_horizontal, name(), "radiosity horizontal");
        label_texture(blur_.second_output, name(), "radiosity output");
        label_texture(blur_.key, name(), "key");
    }

    void run(FrameResources& frame) override {
        // The extent is a fraction of the AO radius, which is the SAO pass's.
        apply_blur_settings(blur_, frame.settings->blur, frame.value("sao.radius"));
        // E's reach while the history is short, in radiosity radii.
        blur_.second_extent_start = early_radiosity_reach * frame.value("radiosity.radius");
        const GLuint sources[] = {frame.texture("ao.temporal"),
                                  frame.texture("radiosity.irradiance.layer0")};
        run_bilateral_blur(blur_, sources, frame.texture("depth_pyramid"),
                           frame.texture("gbuffer.normal"), frame.empty_vertex_array);
        frame.publish("ao.blurred", blur_.output.get());
        frame.publish("radiosity.blurred", blur_.second_output.get());
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        return {{.name = "ao-blurred",
                 .texture = blur_.output.get(),
                 .width = blur_.width,
                 .height = blur_.height,
                 .channels = 1},
                {.name = "radiosity-blurred",
                 .texture = blur_.second_output.get(),
                 .width = blur_.width,
                 .height = blur_.height},
                {.name = "radiosity-blurred-confidence",
                 .texture = blur_.second_output.get(),
                 .width = blur_.width,
                 .height = blur_.height,
                 .channels = 1,
                 .decode = OutputDecode::alpha}};
    }

private:
    BilateralBlur blur_;
};

}  // namespace

BilateralBlur create_bilateral_blur(const ShaderLoader& loader, int source_count,
                                    const BilateralBlurParameters& parameters) {
    check_parameters(parameters);
    if (source_count < 1 || source_count > max_blur_sources)
        throw InputError(fmt::format("the bilateral blur filters 1 to {} sources, not {}",
                                     max_blur_sources, source_count));
    BilateralBlur blur;
    blur.parameters = parameters;
    blur.source_count = source_count;
    blur.key_program = build_fullscreen_program(loader, "bilateral_blur_key.frag");
    blur.program = build_fullscreen_program(loader, "bilateral_blur.frag",
                                            fmt::format("#define BLUR_SOURCES {}\n", source_count));
    return blur;
}

void apply_blur_settings(BilateralBlur& blur, const BlurSettings& settings, float ao_radius) {
    // validate() has checked both factors when the renderer took the settings.
    blur.parameters = settings;
    blur.world_extent = settings.extent * ao_radius;
}

void resize_bilateral_blur(BilateralBlur& blur, int width, int height,
                           std::span<const GLenum> internal_formats) {
    if (int(internal_formats.size()) != blur.source_count)
        throw InputError(fmt::format("the bilateral blur has {} sources but got {} formats",
                                     blur.source_count, internal_formats.size()));
    blur.width = width;
    blur.height = height;
    blur.key = gl::create_texture_2d(GL_RGBA32F, width, height);
    blur.key_framebuffer = framebuffer_for(blur.key, "bilateral blur key");
    gl::Texture* horizontal[max_blur_sources] = {&blur.horizontal, &blur.second_horizontal};
    gl::Texture* output[max_blur_sources] = {&blur.output, &blur.second_output};
    for (int i = 0; i < blur.source_count; ++i) {
        *horizontal[i] = gl::create_texture_2d(internal_formats[std::size_t(i)], width, height);
        *output[i] = gl::create_texture_2d(internal_formats[std::size_t(i)], width, height);
    }
    blur.horizontal_framebuffer =
        framebuffer_for_all(horizontal, blur.source_count, "bilateral blur");
    blur.output_framebuffer = framebuffer_for_all(output, blur.source_count, "bilateral blur");
}

void run_bilateral_blur(const BilateralBlur& blur, std::span<const GLuint> sources,
                        GLuint depth_pyramid, GLuint gbuffer_normal, GLuint empty_vertex_array) {
    if (int(sources.size()) != blur.source_count)
        throw InputError(fmt::format("the bilateral blur has {} sources but got {} textures",
                                     blur.source_count, sources.size()));
    glBindTextureUnit(depth_binding, depth_pyramid);
    glBindTextureUnit(normal_binding, gbuffer_normal);
    glUseProgram(blur.key_program.get());
    begin_fullscreen(blur.key_framebuffer.get(), blur.width, blur.height);
    draw_fullscreen_triangle(empty_vertex_array);

    const GLuint program = blur.program.get();
    glUseProgram(program);
    blur.block.bind({.depth_tolerance = blur.parameters.depth_tolerance,
                     .normal_power = blur.parameters.normal_power,
                     .plane_tolerance = blur.parameters.plane_tolerance,
                     .world_extent = blur.world_extent,
                     .second_extent_start = blur.second_extent_start,
                     .unused0 = 0.0f,
                     .unused1 = 0.0f,
                     .unused2 = 0.0f});
    glBindTextureUnit(key_binding, blur.key.get());

    for (int i = 0; i < blur.source_count; ++i)
        glBindTextureUnit(source_bindings[i], sources[std::size_t(i)]);
    glProgramUniform2i(program, direction_location, 1, 0);
    begin_fullscreen(blur.horizontal_framebuffer.get(), blur.width, blur.height);
    draw_fullscreen_triangle(empty_vertex_array);

    const GLuint horizontal[max_blur_sources] = {blur.horizontal.get(),
                                                 blur.second_horizontal.get()};
    for (int i = 0; i < blur.source_count; ++i)
        glBindTextureUnit(source_bindings[i], horizontal[i]);
    glProgramUniform2i(program, direction_location, 0, 1);
    begin_fullscreen(blur.output_framebuffer.get(), blur.width, blur.height);
    draw_fullscreen_triangle(empty_vertex_array);
}

std::unique_ptr<Pass> make_blur_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<BlurPass>(loader);
}

}  // namespace deepgi
