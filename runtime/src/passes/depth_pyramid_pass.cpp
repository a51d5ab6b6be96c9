// Camera-space depth pyramid (design.md 3, step 2): compute shaders write one
// MIP level at a time through image units, so no level is ever sampled while
// it is being written.
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <algorithm>
#include <bit>

namespace deepgi {

namespace {

constexpr int group_size = 8;  // local_size of depth_pyramid.comp

int level_extent(int extent, int level) {
    return std::max(1, extent >> level);
}

void dispatch_over(int width, int height) {
    glDispatchCompute(GLuint((width + group_size - 1) / group_size),
                      GLuint((height + group_size - 1) / group_size), 1);
}

}  // namespace

DepthPyramidPass create_depth_pyramid_pass(const ShaderLoader& loader, int width, int height,
                                           int max_level) {
    DepthPyramidPass pass;
    pass.width = width;
    pass.height = height;
    const int deepest_possible =
        std::bit_width(unsigned(std::max(width, height))) - 1;  // floor(log2)
    pass.levels = std::clamp(max_level, 0, deepest_possible) + 1;
    pass.base_level = loader.build_program({{GL_COMPUTE_SHADER, "depth_pyramid.comp"}},
                                           "#define PYRAMID_BASE_LEVEL 1\n");
    pass.reduce = loader.build_program({{GL_COMPUTE_SHADER, "depth_pyramid.comp"}});
    pass.pyramid = gl::create_texture(GL_TEXTURE_2D);
    glTextureStorage2D(pass.pyramid.get(), pass.levels, GL_RG32F, width, height);
    glTextureParameteri(pass.pyramid.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glTextureParameteri(pass.pyramid.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(pass.pyramid.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(pass.pyramid.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return pass;
}

void run_depth_pyramid_pass(const DepthPyramidPass& pass, const GBufferTargets& gbuffer) {
    const GLuint pyramid = pass.pyramid.get();
    glUseProgram(pass.base_level.get());
    glBindTextureUnit(DEEPGI_UNIT_GBUFFER_DEPTH, gbuffer.depth.get());
    glBindImageTexture(DEEPGI_IMAGE_PYRAMID_DESTINATION, pyramid, 0, GL_FALSE, 0, GL_WRITE_ONLY,
                       GL_RG32F);
    dispatch_over(pass.width, pass.height);

    glUseProgram(pass.reduce.get());
    for (int level = 1; level < pass.levels; ++level) {
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glBindImageTexture(DEEPGI_IMAGE_PYRAMID_SOURCE, pyramid, level - 1, GL_FALSE, 0,
                           GL_READ_ONLY, GL_RG32F);
        glBindImageTexture(DEEPGI_IMAGE_PYRAMID_DESTINATION, pyramid, level, GL_FALSE, 0,
                           GL_WRITE_ONLY, GL_RG32F);
        dispatch_over(level_extent(pass.width, level), level_extent(pass.height, level));
    }
    // Later passes sample the pyramid with texelFetch; tests read it back.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

FloatImage read_depth_pyramid_level(const DepthPyramidPass& pass, int level) {
    FloatImage image;
    image.width = level_extent(pass.width, level);
    image.height = level_extent(pass.height, level);
    image.channels = 3;
    const std::size_t count = std::size_t(image.width) * std::size_t(image.height);
    std::vector<float> packed(count * 2);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(pass.pyramid.get(), level, GL_RG, GL_FLOAT,
                      GLsizei(packed.size() * sizeof(float)), packed.data());
    image.pixels.assign(count * 3, 0.0f);
    for (std::size_t i = 0; i < count; ++i) {
        image.pixels[3 * i] = packed[2 * i];
        image.pixels[3 * i + 1] = packed[2 * i + 1];
    }
    return image;
}

}  // namespace deepgi
