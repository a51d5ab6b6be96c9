#version 450 core
// Alpha-masked casters: a hole in the surface lets the light through.
#include "alpha_mask.glsl"

void main() {
  if (masked_out()) discard;
}
