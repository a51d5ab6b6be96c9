#version 450 core
// Alpha-masked casters: a hole in the surface lets the light through.
// shadow_pass.cpp hands draw_scene_depth the same binding.
#define ALPHA_MASK_BASE_COLOUR_BINDING 9
#include "alpha_mask.glsl"

void main() {
  if (masked_out()) discard;
}
