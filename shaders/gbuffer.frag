#version 450 core
// Variants (defines from gbuffer_pass.cpp):
//   none               peel, layer 0: nearest surface, no test
//   PEEL_SECOND_LAYER  peel, layer 1 against this frame's layer-0 depth
//   SINGLE_PASS        previous / reproject: gl_Layer says which layer
//   PREDICTION_LAYER   delay / predict: gl_Layer says which layer; layer 2 is
//                      depth only, placed by the next frame's camera (gbuffer.vert)
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"

in GBufferVertex {
  vec3 camera_normal;
  vec2 uv;
  vec4 colour;
  float camera_depth;
  float previous_camera_depth;
  vec4 current_clip;
  vec4 previous_clip;
} fragment_in;

layout(location = DEEPGI_GBUFFER_OUTPUT_NORMAL) out vec2 out_normal;
layout(location = DEEPGI_GBUFFER_OUTPUT_ALBEDO) out vec4 out_albedo;
layout(location = DEEPGI_GBUFFER_OUTPUT_EMISSIVE) out vec3 out_emissive;
// xy: pixels moved since last frame; z: the point's linear depth in the
// previous camera (0: it was behind that camera), which temporal filters
// compare with their stored depth to reject history.
layout(location = DEEPGI_GBUFFER_OUTPUT_MOTION) out vec4 out_motion;

// Bindings are this shader's own; gbuffer_pass.cpp binds the same numbers.
// Layer-0 depth (stored near/z): this frame's for peel, the previous frame's otherwise.
layout(binding = 5) uniform sampler2D reference_depth;
layout(binding = 9) uniform sampler2D base_colour_texture;

layout(location = DEEPGI_UNIFORM_BASE_COLOUR_FACTOR) uniform vec4 base_colour_factor;
layout(location = DEEPGI_UNIFORM_EMISSIVE_FACTOR) uniform vec3 emissive_factor;
layout(location = DEEPGI_UNIFORM_HAS_BASE_COLOUR_TEXTURE) uniform int has_base_colour_texture;
layout(binding = 24) uniform sampler2D emissive_texture;
layout(location = DEEPGI_UNIFORM_HAS_EMISSIVE_TEXTURE) uniform int has_emissive_texture;
layout(location = DEEPGI_UNIFORM_ALPHA_CUTOFF) uniform float alpha_cutoff;
layout(location = DEEPGI_UNIFORM_MATERIAL_SURFACE) uniform vec2 material_surface;  // roughness, metallic
layout(location = DEEPGI_UNIFORM_MIRROR_ROUGHNESS) uniform float mirror_roughness;

float reference_linear_depth(ivec2 pixel) {
  return linear_depth_from_stored(texelFetch(reference_depth, pixel, 0).r, frame.camera_ray_scale.z);
}

// Layer 1 keeps only fragments at least min-separation behind layer 0, compared
// in linear camera depth (the hyperbolic encoding would make dz depth dependent).
bool is_separated_from_layer0() {
  float min_separation = frame.min_separation;
  if (frame.generator == DEEPGI_GENERATOR_REPROJECT) {
    // Where was this point last frame, and how far was layer 0 there?
    if (fragment_in.previous_clip.w <= 0.0) return false;
    vec2 previous_ndc = fragment_in.previous_clip.xy / fragment_in.previous_clip.w;
    ivec2 pixel = ivec2(floor((previous_ndc * 0.5 + 0.5) * frame.internal_size.xy));
    ivec2 size = ivec2(frame.internal_size.xy);
    if (any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(pixel, size))) return false;
    return fragment_in.previous_camera_depth >= reference_linear_depth(pixel) + min_separation;
  }
  return fragment_in.camera_depth >= reference_linear_depth(ivec2(gl_FragCoord.xy)) + min_separation;
}

void main() {
#if defined(PEEL_SECOND_LAYER)
  bool second_layer = true;
#elif defined(SINGLE_PASS)
  bool second_layer = gl_Layer == 1;
#else
  bool second_layer = false;
#endif
  // glTF base colour: factor x texture x vertex colour, alpha included.
  vec4 base_colour = base_colour_factor * fragment_in.colour;
  if (has_base_colour_texture != 0) base_colour *= texture(base_colour_texture, fragment_in.uv);
  // Sampled before any discard, where implicit derivatives are still defined.
  vec3 emissive = emissive_factor;
  if (has_emissive_texture != 0) emissive *= texture(emissive_texture, fragment_in.uv).rgb;
  // An alpha-masked hole is no surface in either layer, so layer 1 sees through it too.
  if (base_colour.a < alpha_cutoff) discard;
#if defined(PREDICTION_LAYER)
  // The prediction is the next frame's layer 0: nearest surface, no
  // separation; only its depth is read, so the colour outputs stay empty.
  if (gl_Layer == 2) {
    out_normal = vec2(0.0);
    out_albedo = vec4(0.0);
    out_emissive = vec3(0.0);
    out_motion = vec4(0.0);
    return;
  }
#endif
  if (second_layer && !is_separated_from_layer0()) discard;

  vec3 albedo = base_colour.rgb;
  out_normal = encode_normal(normalize(fragment_in.camera_normal));
  // Albedo's alpha carries the mirror flag (gbuffer_encoding.glsl).
  bool mirror = material_surface.x <= mirror_roughness && material_surface.y >= 0.5;
  out_albedo = vec4(srgb_encode(albedo), mirror ? gbuffer_mirror_alpha : 1.0);

  // Emissive is read from layer 0 only; motion from both (temporal filters).
  out_emissive = second_layer ? vec3(0.0) : emissive;
  vec4 motion = vec4(0.0);
  if (fragment_in.previous_clip.w > 0.0) {
    vec2 current_ndc = fragment_in.current_clip.xy / fragment_in.current_clip.w;
    vec2 previous_ndc = fragment_in.previous_clip.xy / fragment_in.previous_clip.w;
    motion = vec4((current_ndc - previous_ndc) * 0.5 * frame.internal_size.xy, fragment_in.previous_clip.w, 0.0);
  }
  out_motion = motion;
}
