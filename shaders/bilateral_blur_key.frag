#version 450 core
// The bilateral blur's key, written once before its two directions: layer 0's
// decoded camera-space normal (xyz) and linear depth (w, 0 = no surface). Each
// blur tap then makes one fetch of this instead of two (the depth pyramid and
// the octahedral G-buffer normal) and skips the normal decode, which together
// were most of the blur's cost on llvmpipe (docs/radiosity.md, "The blur").
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"

// Bindings are this shader's own; bilateral_blur_pass.cpp binds the same numbers.
layout(binding = 10) uniform sampler2D depth_key;  // level 0, R: layer-0 linear depth
layout(binding = 0) uniform sampler2DArray gbuffer_normal;

layout(location = 0) out vec4 out_key;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(depth_key, pixel, 0).r;
  vec3 normal = depth > 0.0 ? decode_normal(texelFetch(gbuffer_normal, ivec3(pixel, 0), 0).xy) : vec3(0.0);
  out_key = vec4(normal, depth);
}
