#version 450 core
// The back-face depth pass (backface_depth.frag): positions alone, plus the
// alpha test's inputs (alpha_mask.glsl) when ALPHA_MASK is defined.
#include "frame_constants.glsl"

layout(location = DEEPGI_ATTRIBUTE_POSITION) in vec3 position;
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
  gl_Position = frame.projection * (frame.view * vec4(position, 1.0));
}
