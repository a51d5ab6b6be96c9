#version 450 core
// Where the solid behind each G-buffer layer ends (docs/deep-sao.md, "The
// march"): drawn with front faces culled, one draw per layer, keeping only
// back faces at or behind that layer's stored depth; the reversed-Z depth
// test keeps the nearest of them. For closed meshes seen from outside that is
// the far side of the object the layer shows. The march reads it as the
// depth of that object; 0 (nothing kept) leaves it to the fixed thickness.
// Alpha-masked batches are drawn with ALPHA_MASK defined: a masked-out back
// face is no surface, as it is none in the G-buffer.
#include "shared_constants.h"
// Bindings are this shader's own; backface_depth_pass.cpp binds the same numbers.
#if defined(ALPHA_MASK)
#define ALPHA_MASK_BASE_COLOUR_BINDING 9
#include "alpha_mask.glsl"
#endif

layout(binding = 4) uniform sampler2DArray gbuffer_depth;  // reversed Z
layout(location = 39) uniform int layer;

void main() {
  float stored = texelFetch(gbuffer_depth, ivec3(gl_FragCoord.xy, layer), 0).r;
  // Reversed Z: a smaller value is further away. No surface stored, or a back
  // face in front of the stored one (inside an open mesh): nothing to keep.
  if (stored <= 0.0 || gl_FragCoord.z > stored) discard;
#if defined(ALPHA_MASK)
  if (masked_out()) discard;
#endif
}
