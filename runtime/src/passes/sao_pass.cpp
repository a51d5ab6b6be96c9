// Deep SAO (design.md 3, step 4). The tap pattern is whatever ao_taps.glsl the
// shader loader finds: the build's generated header in the renderer, a header
// written at run time by the noise study and the tests.
#include "deepgi/errors.hpp"
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>

#include <cmath>

namespace deepgi {

void validate_ao_settings(const AoSettings& settings) {
    auto positive = [](float value) { return std::isfinite(value) && value > 0.0f; };
    if (!positive(settings.radius))
        throw InputError("AO radius must be a finite number of metres > 0");
    if (!(std::isfinite(settings.bias) && settings.bias >= 0.0f))
        throw InputError("AO bias must be a finite number of metres >= 0");
    if (!positive(settings.intensity)) throw InputError("AO intensity must be a finite number > 0");
    if (!(std::isfinite(settings.q) && settings.q >= 1.0f))
        throw InputError("AO q must be a finite number of pixels >= 1");
    if (settings.layers != 1 && settings.layers != 2) {
        throw InputError(fmt::format("AO layers must be 1 or 2, got {}", settings.layers));
    }
    if (settings.method != DEEPGI_AO_METHOD_PUBLISHED &&
        settings.method != DEEPGI_AO_METHOD_SOLID_ANGLE)
        throw InputError(fmt::format("AO method must be 0 or 1, got {}", settings.method));
    if (settings.max_mip_level < 0 || settings.max_mip_level > 15) {
        throw InputError(
            fmt::format("AO max MIP level must be in [0, 15], got {}", settings.max_mip_level));
    }
}

SaoPass create_sao_pass(const ShaderLoader& loader, int width, int height) {
    SaoPass pass;
    pass.width = width;
    pass.height = height;
    const std::vector<ShaderStage> stages = {{GL_VERTEX_SHADER, "fullscreen.vert"},
                                             {GL_FRAGMENT_SHADER, "sao.frag"}};
    pass.one_layer = loader.build_program(stages, "#define AO_LAYERS 1\n");
    pass.two_layers = loader.build_program(stages, "#define AO_LAYERS 2\n");
    pass.visibility = gl::create_texture_2d(GL_R16F, width, height);
    pass.framebuffer = gl::create_framebuffer();
    glNamedFramebufferTexture(pass.framebuffer.get(), GL_COLOR_ATTACHMENT0, pass.visibility.get(),
                              0);
    gl::check_framebuffer(pass.framebuffer, "sao");
    return pass;
}

void run_sao_pass(const SaoPass& pass, const AoSettings& settings, const DepthPyramidPass& pyramid,
                  const GBufferTargets& gbuffer, GLuint empty_vertex_array) {
    const GLuint program = settings.layers == 1 ? pass.one_layer.get() : pass.two_layers.get();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, pass.width, pass.height);
    glBindTextureUnit(DEEPGI_UNIT_DEPTH_PYRAMID, pyramid.pyramid.get());
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_NORMAL, gbuffer.normal.get());
    glProgramUniform4f(program, DEEPGI_UNIFORM_SAO_PARAMETERS, settings.radius, settings.bias,
                       settings.intensity, settings.q);
    glProgramUniform1i(program, DEEPGI_UNIFORM_SAO_MAX_MIP, pyramid.levels - 1);
    glProgramUniform1i(program, DEEPGI_UNIFORM_SAO_METHOD, settings.method);
    glBindFramebuffer(GL_FRAMEBUFFER, pass.framebuffer.get());
    glUseProgram(program);
    draw_fullscreen_triangle(empty_vertex_array);
}

namespace {

FloatImage read_single_channel(GLuint texture, int width, int height) {
    FloatImage image;
    image.width = width;
    image.height = height;
    image.channels = 1;
    image.pixels.resize(std::size_t(width) * std::size_t(height));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(texture, 0, GL_RED, GL_FLOAT, GLsizei(image.pixels.size() * sizeof(float)),
                      image.pixels.data());
    return image;
}

}  // namespace

std::vector<std::string> deep_sao_output_names(const DepthPyramidPass& pyramid) {
    std::vector<std::string> names = {"ao-raw", "ao-blurred"};
    for (int level = 0; level < pyramid.levels; ++level)
        names.push_back(fmt::format("depth_pyramid-level{}", level));
    return names;
}

std::optional<FloatImage> read_deep_sao_output(const DepthPyramidPass& pyramid, const SaoPass& sao,
                                               const BilateralBlurPass& blur,
                                               const std::string& name) {
    if (name == "ao-raw") return read_single_channel(sao.visibility.get(), sao.width, sao.height);
    if (name == "ao-blurred")
        return read_single_channel(blur.output.get(), blur.width, blur.height);
    for (int level = 0; level < pyramid.levels; ++level) {
        if (name == fmt::format("depth_pyramid-level{}", level))
            return read_depth_pyramid_level(pyramid, level);
    }
    return std::nullopt;
}

}  // namespace deepgi
