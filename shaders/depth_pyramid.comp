#version 450 core
// Camera-space depth pyramid (docs/design.md, section 5.5). Level 0 holds the linear
// depth of both G-buffer layers, packed into R and G so one fetch serves both
// layers; 0 means no surface. Level m+1 copies one texel of each 2x2 block of
// level m, the corner chosen by a rotated grid: averaging would invent depths
// between a foreground and a background that no surface has.
//
// Variant PYRAMID_BACK_FACES, for the march (ao_march.glsl, level 0 only) and
// the thick spiral (ao_spiral_thick.glsl), builds an RGBA32F pyramid whose B
// and A hold the linear depth of each layer's back face (backface_depth.frag;
// 0 = none) at the same pixel: a texel's four values come from one source
// pixel, so one fetch per step or tap gives both layers' solids, bit for bit
// what a fetch of the back-face texture at that source pixel, made linear,
// would give. Without it (no other reader wants them) the pyramid stays
// RG32F, half the bytes.
//
// Variant PYRAMID_BASE_LEVEL writes level 0 from the G-buffer depth; the other
// variant writes level `destination_level` from the level above it.
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// Bindings are this shader's own; depth_pyramid_pass.cpp binds the same numbers.
#ifdef PYRAMID_BACK_FACES
#define PYRAMID_FORMAT rgba32f
#else
#define PYRAMID_FORMAT rg32f
#endif
layout(binding = 1, PYRAMID_FORMAT) uniform writeonly image2D destination;
#ifdef PYRAMID_BASE_LEVEL
layout(binding = 4) uniform sampler2DArray gbuffer_depth;
#ifdef PYRAMID_BACK_FACES
layout(binding = 5) uniform sampler2DArray backface_depth;
#endif
#else
layout(binding = 0, PYRAMID_FORMAT) uniform readonly image2D source;
#endif

float linear_depth_or_zero(float stored) { return stored > 0.0 ? frame.camera_ray_scale.z / stored : 0.0; }

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(destination)))) return;
#ifdef PYRAMID_BASE_LEVEL
  float layer0 = texelFetch(gbuffer_depth, ivec3(texel, 0), 0).r;
  float layer1 = texelFetch(gbuffer_depth, ivec3(texel, 1), 0).r;
  vec2 back_faces = vec2(0.0);
#ifdef PYRAMID_BACK_FACES
  back_faces = vec2(linear_depth_or_zero(texelFetch(backface_depth, ivec3(texel, 0), 0).r),
                    linear_depth_or_zero(texelFetch(backface_depth, ivec3(texel, 1), 0).r));
#endif
  imageStore(destination, texel, vec4(linear_depth_or_zero(layer0), linear_depth_or_zero(layer1), back_faces));
#else
  // McGuire et al.'s rotated grid: the chosen corner alternates with the
  // parity of the other axis. Odd sizes: the last row/column clamps.
  ivec2 corner = ivec2((texel.y & 1) ^ 1, (texel.x & 1) ^ 1);
  ivec2 from = min(2 * texel + corner, imageSize(source) - 1);
  imageStore(destination, texel, imageLoad(source, from));
#endif
}
