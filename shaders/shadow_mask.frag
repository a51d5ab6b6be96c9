#version 450 core
// Alpha-masked casters: the same alpha test as gbuffer.frag (factor x texture x
// vertex colour against the cutoff), so shadows have the holes the surface has.
#include "shared_constants.h"

in ShadowVertex {
  vec2 uv;
  float alpha;
} fragment_in;

layout(binding = DEEPGI_UNIT_BASE_COLOUR) uniform sampler2D base_colour_texture;
layout(location = DEEPGI_UNIFORM_BASE_COLOUR_FACTOR) uniform vec4 base_colour_factor;
layout(location = DEEPGI_UNIFORM_HAS_BASE_COLOUR_TEXTURE) uniform int has_base_colour_texture;
layout(location = DEEPGI_UNIFORM_ALPHA_CUTOFF) uniform float alpha_cutoff;

void main() {
  float alpha = base_colour_factor.a * fragment_in.alpha;
  if (has_base_colour_texture != 0) alpha *= texture(base_colour_texture, fragment_in.uv).a;
  if (alpha < alpha_cutoff) discard;
}
