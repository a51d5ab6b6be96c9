// Camera-space depth pyramid (docs/design.md, section 5.5): compute shaders write one
// MIP level at a time through image units, so no level is ever sampled while
// it is being written. RG32F: linear depth of layer 0 (R) and 1 (G), 0 = no
// surface; for the thick spiral RGBA32F, with the linear depth of each
// layer's back face in B and A (0 = none), so that its one fetch per tap
// reads both layers' solids; min(max_mip_level, floor(log2(max(width,
// height)))) + 1 levels.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>

namespace deepgi {

namespace {

// Bindings of depth_pyramid.comp: two textures, and two image units.
constexpr GLuint depth_binding = 4;
constexpr GLuint backface_binding = 5;
constexpr GLuint source_image = 0;
constexpr GLuint destination_image = 1;

constexpr int group_size = 8;  // local_size of depth_pyramid.comp

// The estimators that end each stored surface's solid at its back face (the
// march, the default, and the thick spiral) read the back faces from the
// pyramid, one fetch for both layers' depths and solids; the reflections
// march the back-face texture.
bool carries_back_faces(const RenderSettings& settings) {
    return ao_method_reads_back_faces(settings.ao.method);
}

int level_extent(int extent, int level) {
    return std::max(1, extent >> level);
}

void dispatch_over(int width, int height) {
    glDispatchCompute(GLuint((width + group_size - 1) / group_size),
                      GLuint((height + group_size - 1) / group_size), 1);
}

class DepthPyramidPass final : public Pass {
public:
    explicit DepthPyramidPass(const ShaderLoader& loader) {
        for (bool back_faces : {false, true}) {
            const std::string variant = back_faces ? "#define PYRAMID_BACK_FACES 1\n" : "";
            base_level_[back_faces] =
                loader.build_program({{GL_COMPUTE_SHADER, "depth_pyramid.comp"}},
                                     "#define PYRAMID_BASE_LEVEL 1\n" + variant);
            reduce_[back_faces] =
                loader.build_program({{GL_COMPUTE_SHADER, "depth_pyramid.comp"}}, variant);
        }
    }

    std::string_view name() const override { return "depth_pyramid"; }

    PassDeclaration declaration(const RenderSettings& settings) const override {
        // q is the pyramid's: which level a tap of radius h reads,
        // floor(log2(h / q)), is how the gathers use it.
        PassDeclaration declaration = {
            .reads = {{depth_binding, "gbuffer.depth"}},
            .writes = {"depth_pyramid"},
            .value_writes = {{"depth_pyramid.q", settings.depth_pyramid.q}}};
        if (carries_back_faces(settings))
            declaration.reads.push_back({backface_binding, "backface.depth"});
        return declaration;
    }

    // The format follows the estimator: moving to or from the thick spiral
    // reallocates the pyramid.
    SettingsChange settings_change(const RenderSettings& before,
                                   const RenderSettings& after) const override {
        SettingsChange change = Pass::settings_change(before, after);
        if (carries_back_faces(before) != carries_back_faces(after)) change.reallocate = true;
        return change;
    }

    void resize(FrameResources& frame) override {
        width_ = frame.layout.internal_width;
        height_ = frame.layout.internal_height;
        const int deepest_possible =
            std::bit_width(unsigned(std::max(width_, height_))) - 1;  // floor(log2)
        levels_ = std::clamp(frame.settings->depth_pyramid.max_mip_level, 0, deepest_possible) + 1;
        back_faces_ = carries_back_faces(*frame.settings);
        format_ = back_faces_ ? GL_RGBA32F : GL_RG32F;
        pyramid_ = gl::create_texture(GL_TEXTURE_2D);
        label_texture(pyramid_, name(), "linear depth");
        glTextureStorage2D(pyramid_.get(), levels_, format_, width_, height_);
        glTextureParameteri(pyramid_.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
        glTextureParameteri(pyramid_.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(pyramid_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(pyramid_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        // Passes that build a pyramid of their own beside it (radiosity
        // prepare) size it from this, at resize.
        frame.publish_int("depth_pyramid.max_level", levels_ - 1);
    }

    void run(FrameResources& frame) override {
        const GLuint pyramid = pyramid_.get();
        glUseProgram(base_level_[back_faces_].get());
        glBindImageTexture(destination_image, pyramid, 0, GL_FALSE, 0, GL_WRITE_ONLY, format_);
        dispatch_over(width_, height_);

        glUseProgram(reduce_[back_faces_].get());
        for (int level = 1; level < levels_; ++level) {
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            glBindImageTexture(source_image, pyramid, level - 1, GL_FALSE, 0, GL_READ_ONLY,
                               format_);
            glBindImageTexture(destination_image, pyramid, level, GL_FALSE, 0, GL_WRITE_ONLY,
                               format_);
            dispatch_over(level_extent(width_, level), level_extent(height_, level));
        }
        // Later passes sample the pyramid with texelFetch; tests read it back.
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
        frame.publish("depth_pyramid", pyramid);
        // The deepest level a tap may read.
        frame.publish_int("depth_pyramid.max_level", levels_ - 1);
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        std::vector<PassOutput> list;
        const auto add_levels = [&](const char* prefix, OutputDecode decode) {
            for (int level = 0; level < levels_; ++level)
                list.push_back({.name = fmt::format("{}-level{}", prefix, level),
                                .texture = pyramid_.get(),
                                .level = level,
                                .width = level_extent(width_, level),
                                .height = level_extent(height_, level),
                                .decode = decode});
        };
        add_levels("depth_pyramid", OutputDecode::floats_rg_as_rgb);
        // The thick spiral's back faces (B, A), in metres like the depths.
        if (back_faces_) add_levels("depth_pyramid-backface", OutputDecode::floats_ba_as_rgb);
        return list;
    }

private:
    // Indexed by whether the back faces ride along (PYRAMID_BACK_FACES).
    std::array<gl::Program, 2> base_level_;  // level 0 from the G-buffer depth
    std::array<gl::Program, 2> reduce_;      // level m + 1 from level m
    gl::Texture pyramid_;
    bool back_faces_ = false;
    GLenum format_ = GL_RG32F;
    int width_ = 0;
    int height_ = 0;
    int levels_ = 0;
};

}  // namespace

std::unique_ptr<Pass> make_depth_pyramid_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<DepthPyramidPass>(loader);
}

}  // namespace deepgi
