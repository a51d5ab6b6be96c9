#pragma once
// One struct and two free functions per pass (create, run), each defined in
// the .cpp file named after the pass; frame.cpp calls them in frame order.
#include "deepgi/gl_objects.hpp"
#include "deepgi/renderer.hpp"
#include "scene/scene_gpu.hpp"

namespace deepgi {

// ---- shadow_pass.cpp: depth from the key light ----
struct ShadowPass {
    gl::Program program;
    gl::Texture depth;  // DEPTH_COMPONENT32F, compare mode on for PCF
    gl::Framebuffer framebuffer;
    int size = 0;
    glm::mat4 light_view_projection{1.0f};
    float normal_offset = 0.0f;  // metres along the normal before the lookup, against acne
};
ShadowPass create_shadow_pass(const ShaderLoader& loader, const Scene& scene, int size);
void run_shadow_pass(const ShadowPass& pass, const SceneGpu& scene);

// ---- gbuffer_pass.cpp: the two-layer deep G-buffer ----
struct GBufferTargets {
    gl::Texture normal;    // RG16F array, octahedral camera-space normal
    gl::Texture albedo;    // RGBA8 array, sRGB-encoded by the shader
    gl::Texture emissive;  // R11F_G11F_B10F array (layer 0 read)
    gl::Texture motion;    // RG16F array, pixels moved since last frame (layer 0 read)
    gl::Texture depth;     // DEPTH_COMPONENT32F array, near/z (reversed, infinite)
    // Layer-0 depth copied out after the G-buffer is built: the peel pass's
    // second pass reads it this frame, the single-pass generators next frame.
    gl::Texture reference_depth;
};

struct GBufferPass {
    gl::Program peel_first_layer;
    gl::Program peel_second_layer;
    gl::Program single_pass;  // with the geometry shader
    gl::Framebuffer first_layer_framebuffer;
    gl::Framebuffer second_layer_framebuffer;
    gl::Framebuffer layered_framebuffer;
    GBufferTargets targets;
    int width = 0;
    int height = 0;
};
GBufferPass create_gbuffer_pass(const ShaderLoader& loader, int width, int height);
void run_gbuffer_pass(const GBufferPass& pass, const SceneGpu& scene, Generator generator);

// ---- direct_light_pass.cpp: Lambertian key light on both layers ----
struct DirectLightPass {
    gl::Program program;
    gl::Texture radiance;  // R11F_G11F_B10F array, one layer per G-buffer layer
    gl::Framebuffer layer_framebuffers[2];
    int width = 0;
    int height = 0;
};
DirectLightPass create_direct_light_pass(const ShaderLoader& loader, int width, int height);
void run_direct_light_pass(const DirectLightPass& pass, const GBufferTargets& gbuffer,
                           const ShadowPass& shadow, GLuint empty_vertex_array);

// ---- compose_pass.cpp: layer-0 outgoing radiance ----
struct ComposePass {
    gl::Program program;
    gl::Texture radiance;  // R11F_G11F_B10F
    gl::Framebuffer framebuffer;
    int width = 0;
    int height = 0;
};
ComposePass create_compose_pass(const ShaderLoader& loader, int width, int height);
// `ambient_visibility`: the blurred deep SAO output, multiplied into the ambient term.
void run_compose_pass(const ComposePass& pass, const GBufferTargets& gbuffer,
                      const DirectLightPass& direct, GLuint ambient_visibility,
                      GLuint empty_vertex_array);

// ---- tonemap_pass.cpp: filmic curve, sRGB, guard band cropped ----
struct TonemapPass {
    gl::Program program;
    gl::Texture colour;  // RGBA8, viewport size, sRGB-encoded by the shader
    gl::Framebuffer framebuffer;
    int width = 0;
    int height = 0;
};
TonemapPass create_tonemap_pass(const ShaderLoader& loader, int viewport_width,
                                int viewport_height);
void run_tonemap_pass(const TonemapPass& pass, const ComposePass& compose,
                      GLuint empty_vertex_array);

// ---- debug_view_pass.cpp: one attachment instead of the final image ----
struct DebugViewPass {
    gl::Program program;
};
DebugViewPass create_debug_view_pass(const ShaderLoader& loader);
// Writes into the tonemap pass's output so the display code has one image.
void run_debug_view_pass(const DebugViewPass& pass, const GBufferTargets& gbuffer,
                         const DirectLightPass& direct, GLuint ao_raw, GLuint ao_blurred,
                         const TonemapPass& output, GLuint empty_vertex_array);

// Fullscreen triangle into the bound framebuffer (fullscreen.vert).
void draw_fullscreen_triangle(GLuint empty_vertex_array);

// ==== Deep SAO, depth pyramid and bilateral blur (issue 5; docs/deep-sao.md) ====

// ---- depth_pyramid_pass.cpp: RG32F linear depth of both layers, rotated-grid MIPs ----
struct DepthPyramidPass {
    gl::Program base_level;  // level 0 from the G-buffer depth
    gl::Program reduce;      // level m + 1 from level m
    gl::Texture pyramid;     // RG32F, `levels` MIP levels; 0 = no surface
    int width = 0;
    int height = 0;
    int levels = 0;
};
// Builds min(max_level, floor(log2(max(width, height)))) + 1 levels.
DepthPyramidPass create_depth_pyramid_pass(const ShaderLoader& loader, int width, int height,
                                           int max_level);
void run_depth_pyramid_pass(const DepthPyramidPass& pass, const GBufferTargets& gbuffer);
// Level `level` read back: channel 0 layer 0, channel 1 layer 1, channel 2 zero.
FloatImage read_depth_pyramid_level(const DepthPyramidPass& pass, int level);

// ---- sao_pass.cpp: two-layer scalable ambient obscurance from ao_taps.glsl ----
struct SaoPass {
    gl::Program one_layer;
    gl::Program two_layers;
    gl::Texture visibility;  // R16F ambient visibility, internal size
    gl::Framebuffer framebuffer;
    int width = 0;
    int height = 0;
};
// Throws InputError naming the bad parameter.
void validate_ao_settings(const AoSettings& settings);
SaoPass create_sao_pass(const ShaderLoader& loader, int width, int height);
void run_sao_pass(const SaoPass& pass, const AoSettings& settings, const DepthPyramidPass& pyramid,
                  const GBufferTargets& gbuffer, GLuint empty_vertex_array);

// ---- bilateral_blur_pass.cpp: separable edge-aware blur from blur_kernel.glsl ----
// Tolerances are fractions of the centre pixel's depth.
struct BilateralBlurParameters {
    float depth_tolerance = 0.1f;   // taps whose depth differs by this fraction weigh nothing
    float normal_power = 8.0f;      // weight * max(dot(n_tap, n_centre), 0)^power
    float plane_tolerance = 0.02f;  // distance from the centre's tangent plane that weighs nothing
};
struct BilateralBlurPass {
    gl::Program program;
    gl::Texture horizontal;  // intermediate
    gl::Texture output;      // the blurred result
    gl::Framebuffer horizontal_framebuffer;
    gl::Framebuffer output_framebuffer;
    int width = 0;
    int height = 0;
    BilateralBlurParameters parameters;
};
// `internal_format` is what the source holds (GL_R16F for AO, an RGB format for
// radiosity); the blur itself does not care.
BilateralBlurPass create_bilateral_blur_pass(const ShaderLoader& loader, int width, int height,
                                             GLenum internal_format,
                                             const BilateralBlurParameters& parameters = {});
// Keys: layer 0 of the depth pyramid (level 0, R) and of the G-buffer normal.
void run_bilateral_blur_pass(const BilateralBlurPass& pass, GLuint source, GLuint depth_pyramid,
                             GLuint gbuffer_normal, GLuint empty_vertex_array);

// Dump names of this section's outputs ("ao-raw", "ao-blurred",
// "depth_pyramid-level<m>") and their read-back; nullopt for other names.
std::vector<std::string> deep_sao_output_names(const DepthPyramidPass& pyramid);
std::optional<FloatImage> read_deep_sao_output(const DepthPyramidPass& pyramid, const SaoPass& sao,
                                               const BilateralBlurPass& blur,
                                               const std::string& name);

}  // namespace deepgi
