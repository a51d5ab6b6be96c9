// The alpha test of glTF's MASK mode for the depth-only passes (shadow,
// backface_depth), the same as gbuffer.frag's: base-colour factor x texture x
// vertex colour against the material's cutoff. Their vertex shaders pass the
// texture coordinate and the vertex colour's alpha in a MaskVertex block when
// ALPHA_MASK is defined; only alpha-masked batches are drawn that way
// (draw_scene_depth in scene_gpu.cpp), so opaque ones pay for no texture read.
#include "shared_constants.h"

in MaskVertex {
  vec2 uv;
  float alpha;
} mask_in;

// The including shader chooses the texture's binding (ALPHA_MASK_BASE_COLOUR_BINDING,
// defined first); its pass hands the same number to draw_scene_depth.
layout(binding = ALPHA_MASK_BASE_COLOUR_BINDING) uniform sampler2D base_colour_texture;
layout(location = DEEPGI_UNIFORM_BASE_COLOUR_FACTOR) uniform vec4 base_colour_factor;
layout(location = DEEPGI_UNIFORM_HAS_BASE_COLOUR_TEXTURE) uniform int has_base_colour_texture;
layout(location = DEEPGI_UNIFORM_ALPHA_CUTOFF) uniform float alpha_cutoff;

bool masked_out() {
  float alpha = base_colour_factor.a * mask_in.alpha;
  if (has_base_colour_texture != 0) alpha *= texture(base_colour_texture, mask_in.uv).a;
  return alpha < alpha_cutoff;
}
