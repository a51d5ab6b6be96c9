#pragma once
// One factory per pass, each defined in the .cpp file named after the pass
// and declared here from the pass list (pass_list.hpp); the pass classes
// themselves stay private to their files.
#include "pass.hpp"
#include "shader_shared.hpp"

#include <span>

namespace deepgi {

#define DEEPGI_PASS(name) \
    std::unique_ptr<Pass> make_##name##_pass(const ShaderLoader& loader, const Scene& scene);
#include "passes/pass_list.hpp"
#undef DEEPGI_PASS

// The key light's shadow projection for a `size` x `size` map; the shadow pass
// computes it on resize, and the renderer again when the light is edited.
ShadowProjection shadow_projection(const Scene& scene, int size);

// The anti-aliasing filter on its own (the pass copies the display aside and
// runs it back into the display; tests run it on hand-made images).
struct Antialias {
    gl::Program program;
    shader_shared::AntialiasParameters parameters{.edge_threshold = 0.125f,
                                                  .edge_threshold_min = 0.0312f,
                                                  .subpixel = 0.75f,
                                                  .unused0 = 0.0f};
    ParameterBlock<shader_shared::AntialiasParameters> block;
};
Antialias create_antialias(const ShaderLoader& loader);
// Filters `source` (an RGBA8 texture of width x height) into the framebuffer.
void run_antialias(Antialias& antialias, GLuint source, GLuint target_framebuffer, int width,
                   int height, GLuint empty_vertex_array);

// The SAO pass's programs: one per estimator (AO_METHOD, its include of
// sao.frag) and layer count (AO_LAYERS), every one built when the pass is made.
struct SaoProgram {
    AoMethod method = AoMethod::march;
    int layers = 2;
};
std::vector<SaoProgram> sao_program_table();

// Whether the SAO estimator reads its taps' or steps' normals from the
// normal_pair pass (both layers in one fetch) instead of the G-buffer: the
// march, the thick spiral and the solid angle, whose per-layer normal
// fetches were a large part of their pass on llvmpipe (docs/ao-accuracy.md).
constexpr bool ao_method_reads_normal_pair(AoMethod method) {
    return method == AoMethod::march || method == AoMethod::spiral_thick ||
           method == AoMethod::solid_angle;
}

// Whether the reflection pass runs: reflections on and a mirror material in
// the scene (roughness <= mirror_roughness, metallic >= 0.5). The passes it
// needs (back faces) and the compose pass's read follow this.
bool reflections_traced(const Scene& scene, const RenderSettings& settings);

// The separable bilateral blur as a reusable building block: the blur pass
// uses it, and so will any later pass that smooths a screen-space signal.
// Tolerances are fractions of the centre pixel's depth.
// The edge weights are the settings' (one owner for their defaults).
using BilateralBlurParameters = BlurSettings;
// Sources one blur filters with the same weights (one render target each).
inline constexpr int max_blur_sources = 2;
struct BilateralBlur {
    gl::Program program;
    gl::Program key_program;  // writes `key` once, before both directions
    int source_count = 1;
    gl::Texture key;  // RGBA32F: layer-0 camera-space normal (xyz), linear depth (w)
    gl::Framebuffer key_framebuffer;
    gl::Texture horizontal;         // intermediate of the first source
    gl::Texture output;             // the first source blurred
    gl::Texture second_horizontal;  // the same for the second source, when there is one
    gl::Texture second_output;
    gl::Framebuffer horizontal_framebuffer;  // one colour attachment per source
    gl::Framebuffer output_framebuffer;
    int width = 0;
    int height = 0;
    BilateralBlurParameters parameters;
    // Metres: a tap this far from the centre weighs nothing (0: no limit).
    // The settings give it as a fraction of the AO radius (BlurSettings::extent).
    float world_extent = 0.0f;
    // Metres: the second source's reach on the first frame after history was
    // invalidated, divided by the frames since, never below world_extent
    // (BlurParameters in shaders/pass_parameters.h); 0: it shares world_extent.
    float second_extent_start = 0.0f;
    ParameterBlock<shader_shared::BlurParameters> block;  // the above, as the shader reads them
};
// Takes the settings' edge weights and world extent, the latter a fraction of
// the AO radius (read every frame, so the window's sliders act without a
// rebuild); the settings are validated ones.
void apply_blur_settings(BilateralBlur& blur, const BlurSettings& settings, float ao_radius);
// Builds the program for `source_count` (1 or 2) sources; throws InputError
// for bad parameters.
BilateralBlur create_bilateral_blur(const ShaderLoader& loader, int source_count,
                                    const BilateralBlurParameters& parameters = {});
// One internal format per source: what the source holds (GL_R16F for AO,
// signed, GL_RGBA16F for radiosity); the blur itself does not care, as long
// as the format is float (a linear average of signed values).
void resize_bilateral_blur(BilateralBlur& blur, int width, int height,
                           std::span<const GLenum> internal_formats);
// Keys: layer 0 of the depth pyramid (level 0, R) and of the G-buffer normal.
// One source texture per source, in order.
void run_bilateral_blur(const BilateralBlur& blur, std::span<const GLuint> sources,
                        GLuint depth_pyramid, GLuint gbuffer_normal, GLuint empty_vertex_array);

}  // namespace deepgi
