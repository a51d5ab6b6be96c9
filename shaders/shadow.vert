#version 450 core
#include "shared_constants.h"
// Depth only, unless ALPHA_MASK (shadow_mask.frag) is defined: then the mask
// inputs of gbuffer.frag are passed on, so a hole lets the light through.
layout(location = DEEPGI_ATTRIBUTE_POSITION) in vec3 position;
layout(location = DEEPGI_UNIFORM_LIGHT_VIEW_PROJECTION) uniform mat4 light_view_projection;
#if defined(ALPHA_MASK)
layout(location = DEEPGI_ATTRIBUTE_UV) in vec2 uv;
layout(location = DEEPGI_ATTRIBUTE_COLOUR) in vec4 colour;
out ShadowVertex {
  vec2 uv;
  float alpha;
} vertex_out;
#endif

void main() {
#if defined(ALPHA_MASK)
  vertex_out.uv = uv;
  vertex_out.alpha = colour.a;
#endif
  gl_Position = light_view_projection * vec4(position, 1.0);
}
