// Frame statistics (frame_statistics.comp): the log-average luminance of the
// lit image before the tonemap, the exposure in use (the setting, or with
// `--exposure auto` key / log-average, clamped and smoothed over frames),
// and the near and far depth of each G-buffer layer's valid texels, which
// the depth debug views are scaled by. The result is a 2x1 RGBA32F texture,
// "frame_statistics", that the tonemap and the debug view read on the GPU:
// the frame never waits for a readback. The CPU reads those 32 bytes only
// when asked (Renderer::frame_statistics()).
#include "passes/passes.hpp"
#include "shader_shared.hpp"

namespace deepgi {

namespace {

// Bindings of frame_statistics.comp.
constexpr GLuint radiance_binding = 8;
constexpr GLuint depth_binding = 4;
constexpr GLuint statistics_image = 0;
constexpr GLuint partials_buffer = 0;
constexpr int tile = 64;           // pixels per side of one group of the partials stage
constexpr int partial_floats = 8;  // struct Partial
// Uniform locations.
constexpr GLint key_location = 0;
constexpr GLint limits_location = 1;
constexpr GLint restart_location = 2;
constexpr GLint smoothing_location = 3;
constexpr GLint count_location = 4;

class FrameStatisticsPass final : public Pass {
public:
    explicit FrameStatisticsPass(const ShaderLoader& loader)
        : partials_(loader.build_program({{GL_COMPUTE_SHADER, "frame_statistics.comp"}},
                                         "#define FRAME_STATISTICS_PARTIALS 1\n")),
          total_(loader.build_program({{GL_COMPUTE_SHADER, "frame_statistics.comp"}})) {
        statistics_ = gl::create_texture(GL_TEXTURE_2D);
        label_texture(statistics_, name(), "statistics");
        glTextureStorage2D(statistics_.get(), 1, GL_RGBA32F, 2, 1);
        const float zero[8] = {};
        glTextureSubImage2D(statistics_.get(), 0, 0, 0, 2, 1, GL_RGBA, GL_FLOAT, zero);
        const GLuint total = total_.get();
        glProgramUniform1f(total, key_location, auto_exposure_key);
        glProgramUniform2f(total, limits_location, auto_exposure_min, auto_exposure_max);
        glProgramUniform1f(total, smoothing_location, auto_exposure_smoothing);
    }

    std::string_view name() const override { return "frame_statistics"; }

    PassDeclaration declaration(const RenderSettings&) const override {
        return {.reads = {{radiance_binding, "compose.radiance"}, {depth_binding, "gbuffer.depth"}},
                .writes = {"frame_statistics"}};
    }

    void resize(FrameResources& frame) override {
        groups_x_ = (frame.settings->width + tile - 1) / tile;
        groups_y_ = (frame.settings->height + tile - 1) / tile;
        partials_buffer_ = gl::create_buffer();
        glNamedBufferStorage(partials_buffer_.get(),
                             GLsizeiptr(groups_x_) * groups_y_ * partial_floats * sizeof(float),
                             nullptr, 0);
    }

    void run(FrameResources& frame) override {
        const bool automatic = frame.settings->exposure == auto_length;
        // The smoothing starts afresh where there is no history to smooth
        // against: the first frame after an invalidation, or after frames
        // with a manual exposure.
        const bool restart = !frame.history_valid() || !last_frame_automatic_;
        last_frame_automatic_ = automatic;
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, partials_buffer, partials_buffer_.get());
        glUseProgram(partials_.get());
        glDispatchCompute(GLuint(groups_x_), GLuint(groups_y_), 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glBindImageTexture(statistics_image, statistics_.get(), 0, GL_FALSE, 0, GL_READ_WRITE,
                           GL_RGBA32F);
        glProgramUniform1i(total_.get(), restart_location, restart ? 1 : 0);
        glProgramUniform1i(total_.get(), count_location, groups_x_ * groups_y_);
        glUseProgram(total_.get());
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                        GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        frame.publish("frame_statistics", statistics_.get());
    }

private:
    gl::Program partials_;  // one sum per 64x64 tile
    gl::Program total_;     // the tiles' sums, the exposure and the ranges
    gl::Texture statistics_;
    gl::Buffer partials_buffer_;
    int groups_x_ = 0;
    int groups_y_ = 0;
    bool last_frame_automatic_ = false;
};

}  // namespace

std::unique_ptr<Pass> make_frame_statistics_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<FrameStatisticsPass>(loader);
}

}  // namespace deepgi
