// The two-layer deep G-buffer (docs/design.md, section 5.2) with its five generators.
// The depth layer 1 is peeled against goes into the "layer0-depth" history
// pair after the G-buffer is built: this frame's layer 0, which the peel
// generator's second pass reads this frame and previous/reproject read the
// next; or, for delay and predict, the third layer: this frame's geometry seen
// by the next frame's camera, i.e. the next frame's layer 0 when the camera
// arrives where expected (the paper's Delay and Predict variants).
#include "deepgi/errors.hpp"
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>

namespace deepgi {

namespace {

constexpr GLenum all_outputs[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                                  GL_COLOR_ATTACHMENT3};
constexpr const char* layer0_depth_history = "layer0-depth";

// Texture bindings of gbuffer.frag: the layer-0 depth the second layer is
// compared against, and the materials' textures (bound by draw_scene).
constexpr GLuint reference_depth_binding = 5;
constexpr MaterialTextureBindings material_bindings = {.base_colour = 9, .emissive = 24};

struct GBufferTargets {
    gl::Texture normal;    // RG16F array, octahedral camera-space normal
    gl::Texture albedo;    // RGBA8 array, sRGB-encoded by the shader
    gl::Texture emissive;  // R11F_G11F_B10F array (layer 0 read)
    gl::Texture motion;    // RGBA16F array: pixels moved since last frame, previous linear depth
    gl::Texture depth;     // DEPTH_COMPONENT32F array, near/z (reversed, infinite)
    // Delay and predict: 3, the third layer of each being the prediction
    // (depth; the colour layers are there because layered rendering needs
    // every attachment to have the layer). Otherwise DEEPGI_LAYER_COUNT.
    int layers = DEEPGI_LAYER_COUNT;
};

constexpr int prediction_layer = 2;

// The single-pass generators write gl_Layer from the vertex shader (gbuffer.vert).
constexpr const char* vertex_layer_extension = "GL_ARB_shader_viewport_layer_array";

int gbuffer_layers(Generator generator) {
    return generator_predicts_next_frame(generator) ? prediction_layer + 1 : DEEPGI_LAYER_COUNT;
}

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
        // Layer 1 has motion (temporal filters) but no emissive.
        glNamedFramebufferTextureLayer(fb, GL_COLOR_ATTACHMENT0 + DEEPGI_GBUFFER_OUTPUT_MOTION,
                                       targets.motion.get(), 0, layer);
        const GLenum outputs[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_NONE,
                                  GL_COLOR_ATTACHMENT0 + DEEPGI_GBUFFER_OUTPUT_MOTION};
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

class GBufferPass final : public Pass {
public:
    explicit GBufferPass(const ShaderLoader& loader) {
        const std::vector<ShaderStage> two_stages = {{GL_VERTEX_SHADER, "gbuffer.vert"},
                                                     {GL_FRAGMENT_SHADER, "gbuffer.frag"}};
        peel_first_layer_ = loader.build_program(two_stages);
        peel_second_layer_ = loader.build_program(two_stages, "#define PEEL_SECOND_LAYER 1\n");
        // The single-pass generators: no geometry shader; each triangle is
        // drawn once per layer as an instance, the vertex shader choosing the
        // layer. Every layer then goes through the same vertex stage as peel's,
        // so delay's and predict's layers equal peel's bit for bit, and so do
        // previous's and reproject's wherever their reference is this frame's
        // layer 0 (gbuffer.vert says why a geometry shader would not). Without
        // the extension that lets the vertex shader set the layer, peel still
        // runs and the other four are refused, when asked for.
        if (epoxy_has_gl_extension(vertex_layer_extension)) {
            single_pass_ = loader.build_program(two_stages, "#define SINGLE_PASS 1\n");
            prediction_pass_ = loader.build_program(
                two_stages, "#define SINGLE_PASS 1\n#define PREDICTION_LAYER 1\n");
        }
    }

    std::string_view name() const override { return "gbuffer"; }

    PassDeclaration declaration(const RenderSettings& settings) const override {
        // The G-buffer tells mirrors apart; the reflection pass runs for them.
        return {.reads = {},
                .writes = {"gbuffer.normal", "gbuffer.albedo", "gbuffer.emissive", "gbuffer.motion",
                           "gbuffer.depth"},
                .value_writes = {{"gbuffer.mirror_roughness", settings.mirror_roughness}}};
    }

    // Delay and predict keep a third layer the others do not have, so moving
    // between the two kinds reallocates, and the depth in the history pair
    // changes meaning (layer 0 against the prediction), so history goes.
    SettingsChange settings_change(const RenderSettings& before,
                                   const RenderSettings& after) const override {
        SettingsChange change = Pass::settings_change(before, after);
        if (gbuffer_layers(before.generator) != gbuffer_layers(after.generator)) {
            change.reallocate = true;
            if (change.drop_history.empty())
                change.drop_history =
                    fmt::format("generator {} -> {} (the layer 1 reference changes)",
                                to_string(before.generator), to_string(after.generator));
        }
        return change;
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        GBufferTargets& targets = targets_;
        const int layers = gbuffer_layers(frame.settings->generator);
        targets.layers = layers;
        targets.normal = gl::create_texture_array(GL_RG16F, width_, height_, layers);
        targets.albedo = gl::create_texture_array(GL_RGBA8, width_, height_, layers);
        // Layered rendering needs every attachment layered, so emissive and motion
        // carry a second layer that nothing reads.
        targets.emissive = gl::create_texture_array(GL_R11F_G11F_B10F, width_, height_, layers);
        targets.motion = gl::create_texture_array(GL_RGBA16F, width_, height_, layers);
        targets.depth = gl::create_texture_array(GL_DEPTH_COMPONENT32F, width_, height_, layers);
        label_texture(targets.normal, name(), "normal");
        label_texture(targets.albedo, name(), "albedo");
        label_texture(targets.emissive, name(), "emissive");
        label_texture(targets.motion, name(), "motion");
        label_texture(targets.depth, name(), "depth");
        frame.allocate_history(layer0_depth_history, GL_DEPTH_COMPONENT32F, width_, height_);

        first_layer_framebuffer_ = gl::create_framebuffer();
        attach_layer(first_layer_framebuffer_, targets, 0);
        gl::check_framebuffer(first_layer_framebuffer_, "gbuffer layer 0");
        second_layer_framebuffer_ = gl::create_framebuffer();
        attach_layer(second_layer_framebuffer_, targets, 1);
        gl::check_framebuffer(second_layer_framebuffer_, "gbuffer layer 1");

        layered_framebuffer_ = gl::create_framebuffer();
        const GLuint layered = layered_framebuffer_.get();
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
        gl::check_framebuffer(layered_framebuffer_, "gbuffer layered");
    }

    void run(FrameResources& frame) override {
        const HistoryPair& layer0_depth = frame.history(layer0_depth_history);
        glViewport(0, 0, width_, height_);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glDepthMask(GL_TRUE);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        const SceneGpu& scene = *frame.scene_gpu;
        for (const gl::Program* program :
             {&peel_first_layer_, &peel_second_layer_, &single_pass_, &prediction_pass_})
            if (program->get() != 0)
                glProgramUniform1f(program->get(), DEEPGI_UNIFORM_MIRROR_ROUGHNESS,
                                   frame.settings->mirror_roughness);

        if (frame.settings->generator != Generator::peel && single_pass_.get() == 0)
            throw GraphicsError(fmt::format("--generator {} needs {}, which this driver lacks",
                                            to_string(frame.settings->generator),
                                            vertex_layer_extension));
        if (frame.settings->generator == Generator::peel) {
            clear_gbuffer(first_layer_framebuffer_, 4);
            glBindFramebuffer(GL_FRAMEBUFFER, first_layer_framebuffer_.get());
            glUseProgram(peel_first_layer_.get());
            draw_scene(scene, peel_first_layer_.get(), material_bindings);
            copy_depth_layer(0, layer0_depth.written());

            clear_gbuffer(second_layer_framebuffer_, 4);
            // The second layer's emissive is never written by peel; clear it too
            // so every generator leaves the same unused layer behind.
            const float zero[4] = {0, 0, 0, 0};
            glClearTexSubImage(targets_.emissive.get(), 0, 0, 0, 1, width_, height_, 1, GL_RGBA,
                               GL_FLOAT, zero);
            glBindTextureUnit(reference_depth_binding, layer0_depth.written());
            glBindFramebuffer(GL_FRAMEBUFFER, second_layer_framebuffer_.get());
            glUseProgram(peel_second_layer_.get());
            draw_scene(scene, peel_second_layer_.get(), material_bindings);
        } else if (generator_predicts_next_frame(frame.settings->generator)) {
            // Delay / predict: layer 1 against the prediction the last frame
            // made of this frame's layer 0; this frame predicts the next's.
            glBindTextureUnit(reference_depth_binding, layer0_depth.previous());
            clear_gbuffer(layered_framebuffer_, 4);
            glBindFramebuffer(GL_FRAMEBUFFER, layered_framebuffer_.get());
            glUseProgram(prediction_pass_.get());
            draw_scene(scene, prediction_pass_.get(), material_bindings, prediction_layer + 1);
            copy_depth_layer(prediction_layer, layer0_depth.written());
        } else {
            // Previous / reproject: compare against the previous frame's layer 0.
            glBindTextureUnit(reference_depth_binding, layer0_depth.previous());
            clear_gbuffer(layered_framebuffer_, 4);
            glBindFramebuffer(GL_FRAMEBUFFER, layered_framebuffer_.get());
            glUseProgram(single_pass_.get());
            draw_scene(scene, single_pass_.get(), material_bindings, DEEPGI_LAYER_COUNT);
            copy_depth_layer(0, layer0_depth.written());
        }
        frame.publish("gbuffer.normal", targets_.normal.get());
        frame.publish("gbuffer.albedo", targets_.albedo.get());
        frame.publish("gbuffer.emissive", targets_.emissive.get());
        frame.publish("gbuffer.motion", targets_.motion.get());
        frame.publish("gbuffer.depth", targets_.depth.get());
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        std::vector<PassOutput> list;
        auto add = [&](std::string name, const gl::Texture& texture, int layer, int channels,
                       OutputDecode decode) {
            list.push_back({.name = std::move(name),
                            .texture = texture.get(),
                            .layer = layer,
                            .width = width_,
                            .height = height_,
                            .channels = channels,
                            .decode = decode,
                            .mask_depth = targets_.depth.get()});
        };
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer)
            add(fmt::format("gbuffer-depth-layer{}", layer), targets_.depth, layer, 1,
                OutputDecode::depth_to_metres);
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer)
            add(fmt::format("gbuffer-normal-layer{}", layer), targets_.normal, layer, 3,
                OutputDecode::octahedral_normal);
        for (int layer = 0; layer < DEEPGI_LAYER_COUNT; ++layer)
            add(fmt::format("gbuffer-albedo-layer{}", layer), targets_.albedo, layer, 3,
                OutputDecode::srgb_to_linear);
        // Delay and predict: this frame's geometry seen by the next frame's
        // camera, the depth the next frame's layer 1 peels against.
        if (targets_.layers > prediction_layer)
            add("gbuffer-depth-prediction", targets_.depth, prediction_layer, 1,
                OutputDecode::depth_to_metres);
        add("gbuffer-emissive-layer0", targets_.emissive, 0, 3, OutputDecode::floats);
        add("gbuffer-motion-layer0", targets_.motion, 0, 3, OutputDecode::floats_rg_as_rgb);
        return list;
    }

private:
    void copy_depth_layer(int layer, GLuint destination) const {
        glCopyImageSubData(targets_.depth.get(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, destination,
                           GL_TEXTURE_2D, 0, 0, 0, 0, width_, height_, 1);
    }

    gl::Program peel_first_layer_;
    gl::Program peel_second_layer_;
    gl::Program single_pass_;      // two instances, one per layer
    gl::Program prediction_pass_;  // three instances, the third the next frame's layer 0
    gl::Framebuffer first_layer_framebuffer_;
    gl::Framebuffer second_layer_framebuffer_;
    gl::Framebuffer layered_framebuffer_;
    GBufferTargets targets_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_gbuffer_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<GBufferPass>(loader);
}

}  // namespace deepgi
