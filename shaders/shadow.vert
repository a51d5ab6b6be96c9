#version 450 core
#include "shared_constants.h"
// Depth only, unless ALPHA_MASK (shadow_mask.frag) is defined: then the
// inputs of the alpha test (alpha_mask.glsl) are passed on.
layout(location = DEEPGI_ATTRIBUTE_POSITION) in vec3 position;
layout(location = 3) uniform mat4 light_view_projection;
#if defined(ALPHA_MASK)
layout(location = DEEPGI_ATTRIBUTE_UV) in vec2 uv;
layout(location = DEEPGI_ATTRIBUTE_COLOUR) in vec4 colour;
out MaskVertex {
  vec2 uv;
  float alpha;
} mask_out;
#endif

void main() {
#if defined(ALPHA_MASK)
  mask_out.uv = uv;
  mask_out.alpha = colour.a;
#endif
  gl_Position = light_view_projection * vec4(position, 1.0);
}
