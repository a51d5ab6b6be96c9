#pragma once
// One factory per pass, each defined in the .cpp file named after the pass;
// the pass classes themselves stay private to their files. frame.cpp lists
// the factories in the order the passes run.
#include "pass.hpp"
#include "shader_shared.hpp"

#include <span>

namespace deepgi {

std::unique_ptr<Pass> make_shadow_pass(const ShaderLoader& loader, const Scene& scene);
// The key light's shadow projection for a `size` x `size` map; the shadow pass
// computes it on resize, and the renderer again when the light is edited.
ShadowProjection shadow_projection(const Scene& scene, int size);
std::unique_ptr<Pass> make_gbuffer_pass(const ShaderLoader& loader, const Scene& scene);
std::unique_ptr<Pass> make_backface_depth_pass(const ShaderLoader& loader, const Scene& scene);
std::unique_ptr<Pass> make_direct_light_pass(const ShaderLoader& loader, const Scene& scene);
std::unique_ptr<Pass> make_depth_pyramid_pass(const ShaderLoader& loader, const Scene& scene);
std::unique_ptr<Pass> make_sao_pass(const ShaderLoader& loader, const Scene& scene);
std::unique_ptr<Pass> make_ao_temporal_pass(const ShaderLoader& loader, const Scene& scene);
std::unique_ptr<Pass> make_radiosity_prepare_pass(const ShaderLoader& loader, const Scene& scene);
std::unique_ptr<Pass> make_radiosity_pass(const ShaderLoader& loader, const Scene& scene);
// AO and layer 0's radiosity through one bilateral blur.
std::unique_ptr<Pass> make_blur_pass(const ShaderLoader& loader, const Scene& scene);
// Mirror reflections through both layers (reflection_pass.cpp).
std::unique_ptr<Pass> make_reflection_pass(const ShaderLoader& loader, const Scene& scene);
// Whether the reflection pass runs: reflections on and a mirror material in
// the scene (roughness <= mirror_roughness, metallic >= 0.5). The passes it
// needs (back faces) and the compose pass's read follow this.
bool reflections_traced(const Scene& scene, const RenderSettings& settings);
std::unique_ptr<Pass> make_compose_pass(const ShaderLoader& loader, const Scene& scene);
std::unique_ptr<Pass> make_tonemap_pass(const ShaderLoader& loader, const Scene& scene);
std::unique_ptr<Pass> make_debug_view_pass(const ShaderLoader& loader, const Scene& scene);

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
    ParameterBlock<shader_shared::BlurParameters> block;  // the above, as the shader reads them
};
// Takes the settings' edge weights and world extent (read every frame, so the
// window's sliders act without a rebuild); the settings are validated ones.
void apply_blur_settings(BilateralBlur& blur, const RenderSettings& settings);
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
