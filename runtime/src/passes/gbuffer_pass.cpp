#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

namespace {

constexpr GLenum all_outputs[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                                  GL_COLOR_ATTACHMENT3};

void attach_layer(const gl::Framebuffer& framebuffer, const GBufferTargets& targets, int layer) {
    const GLuint fb = framebuffer.get();
    glNamedFramebufferTextureLayer(fb, GL_COLOR_ATTACHMENT0 + DEEPGI_GBUFFER_OUTPUT_NORMAL,
                                   targets.normal.get(), 0, layer);
    glNamedFramebufferTextureLayer(fb, GL_COLOR_ATTACHMENT0 + DEEPGI_GBUFFER_OUTPUT_ALBEDO,
                                   targets.albedo.get(), 0, layer);
    glNamedFramebufferTextureLayer(fb, GL_DEPTH_ATTACHMENT, targets.depth.get(), 0, layer);
    if (layer == 0) {
        glNamedFramebufferTextureLayer(fb, GL_COLOR_ATTACHMENT0 + DEEPGI_GBUFFER_OUTPUT_EMISSIVE,
                                       targets.emissive.get(), 0, 0);
        glNamedFramebufferTextureLayer(fb, GL_COLOR_ATTACHMENT0 + DEEPGI_GBUFFER_OUTPUT_MOTION,
                                       targets.motion.get(), 0, 0);
        glNamedFramebufferDrawBuffers(fb, 4, all_outputs);
    } else {
        const GLenum outputs[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_NONE, GL_NONE};
        glNamedFramebufferDrawBuffers(fb, 4, outputs);
    }
}

void clear_gbuffer(const gl::Framebuffer& framebuffer, int colour_outputs) {
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < colour_outputs; ++i)
        glClearNamedFramebufferfv(framebuffer.get(), GL_COLOR, i, zero);
    const float nothing_hit = 0.0f;  // reversed Z: 0 is infinitely far
    glClearNamedFramebufferfv(framebuffer.get(), GL_DEPTH, 0, &nothing_hit);
}

void copy_layer0_depth_to_reference(const GBufferPass& pass) {
    glCopyImageSubData(pass.targets.depth.get(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0,
                       pass.targets.reference_depth.get(), GL_TEXTURE_2D, 0, 0, 0, 0, pass.width,
                       pass.height, 1);
}

}  // namespace

GBufferPass create_gbuffer_pass(const ShaderLoader& loader, int width, int height) {
    GBufferPass pass;
    pass.width = width;
    pass.height = height;
    const std::vector<ShaderStage> two_stages = {{GL_VERTEX_SHADER, "gbuffer.vert"},
                                                 {GL_FRAGMENT_SHADER, "gbuffer.frag"}};
    pass.peel_first_layer = loader.build_program(two_stages);
    pass.peel_second_layer = loader.build_program(two_stages, "#define PEEL_SECOND_LAYER 1\n");
    pass.single_pass = loader.build_program({{GL_VERTEX_SHADER, "gbuffer.vert"},
                                             {GL_GEOMETRY_SHADER, "gbuffer.geom"},
                                             {GL_FRAGMENT_SHADER, "gbuffer.frag"}},
                                            "#define SINGLE_PASS 1\n");

    GBufferTargets& targets = pass.targets;
    targets.normal = gl::create_texture_array(GL_RG16F, width, height, DEEPGI_LAYER_COUNT);
    targets.albedo = gl::create_texture_array(GL_RGBA8, width, height, DEEPGI_LAYER_COUNT);
    // Layered rendering needs every attachment layered, so emissive and motion
    // carry a second layer that nothing reads.
    targets.emissive =
        gl::create_texture_array(GL_R11F_G11F_B10F, width, height, DEEPGI_LAYER_COUNT);
    targets.motion = gl::create_texture_array(GL_RG16F, width, height, DEEPGI_LAYER_COUNT);
    targets.depth =
        gl::create_texture_array(GL_DEPTH_COMPONENT32F, width, height, DEEPGI_LAYER_COUNT);
    targets.reference_depth = gl::create_texture_2d(GL_DEPTH_COMPONENT32F, width, height);
    const float nothing_hit = 0.0f;
    glClearTexImage(targets.reference_depth.get(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &nothing_hit);

    pass.first_layer_framebuffer = gl::create_framebuffer();
    attach_layer(pass.first_layer_framebuffer, targets, 0);
    gl::check_framebuffer(pass.first_layer_framebuffer, "gbuffer layer 0");
    pass.second_layer_framebuffer = gl::create_framebuffer();
    attach_layer(pass.second_layer_framebuffer, targets, 1);
    gl::check_framebuffer(pass.second_layer_framebuffer, "gbuffer layer 1");

    pass.layered_framebuffer = gl::create_framebuffer();
    const GLuint layered = pass.layered_framebuffer.get();
    glNamedFramebufferTexture(layered, GL_COLOR_ATTACHMENT0 + DEEPGI_GBUFFER_OUTPUT_NORMAL,
                              targets.normal.get(), 0);
    glNamedFramebufferTexture(layered, GL_COLOR_ATTACHMENT0 + DEEPGI_GBUFFER_OUTPUT_ALBEDO,
                              targets.albedo.get(), 0);
    glNamedFramebufferTexture(layered, GL_COLOR_ATTACHMENT0 + DEEPGI_GBUFFER_OUTPUT_EMISSIVE,
                              targets.emissive.get(), 0);
    glNamedFramebufferTexture(layered, GL_COLOR_ATTACHMENT0 + DEEPGI_GBUFFER_OUTPUT_MOTION,
                              targets.motion.get(), 0);
    glNamedFramebufferTexture(layered, GL_DEPTH_ATTACHMENT, targets.depth.get(), 0);
    glNamedFramebufferDrawBuffers(layered, 4, all_outputs);
    gl::check_framebuffer(pass.layered_framebuffer, "gbuffer layered");
    return pass;
}

void run_gbuffer_pass(const GBufferPass& pass, const SceneGpu& scene, Generator generator) {
    glViewport(0, 0, pass.width, pass.height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glBindTextureUnit(DEEPGI_UNIT_REFERENCE_DEPTH, pass.targets.reference_depth.get());

    if (generator == Generator::peel) {
        clear_gbuffer(pass.first_layer_framebuffer, 4);
        glBindFramebuffer(GL_FRAMEBUFFER, pass.first_layer_framebuffer.get());
        glUseProgram(pass.peel_first_layer.get());
        draw_scene(scene, pass.peel_first_layer.get());
        copy_layer0_depth_to_reference(pass);

        clear_gbuffer(pass.second_layer_framebuffer, 2);
        // The second layer's emissive and motion are never written by peel; clear
        // them too so every generator leaves the same unused layer behind.
        const float zero[4] = {0, 0, 0, 0};
        glClearTexSubImage(pass.targets.emissive.get(), 0, 0, 0, 1, pass.width, pass.height, 1,
                           GL_RGBA, GL_FLOAT, zero);
        glClearTexSubImage(pass.targets.motion.get(), 0, 0, 0, 1, pass.width, pass.height, 1,
                           GL_RGBA, GL_FLOAT, zero);
        glBindFramebuffer(GL_FRAMEBUFFER, pass.second_layer_framebuffer.get());
        glUseProgram(pass.peel_second_layer.get());
        draw_scene(scene, pass.peel_second_layer.get());
        return;
    }

    // Previous / reproject: the reference still holds last frame's layer 0.
    clear_gbuffer(pass.layered_framebuffer, 4);
    glBindFramebuffer(GL_FRAMEBUFFER, pass.layered_framebuffer.get());
    glUseProgram(pass.single_pass.get());
    draw_scene(scene, pass.single_pass.get());
    copy_layer0_depth_to_reference(pass);
}

}  // namespace deepgi
