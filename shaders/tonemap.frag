#version 450 core
// Filmic tonemap (Hable's curve), sRGB encode, guard band cropped: the output
// is viewport sized and reads the composed radiance offset by the guard band.
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"
#include "tonemap_curve.glsl"

// Bindings are this shader's own; tonemap_pass.cpp binds the same numbers.
layout(binding = 8) uniform sampler2D composed_radiance;
// frame_statistics.comp's result: texel 0's x is the exposure in use.
layout(binding = 9) uniform sampler2D frame_statistics;
layout(location = 0) out vec4 out_colour;

void main() {
  ivec2 source = ivec2(gl_FragCoord.xy) + ivec2(frame.guard_band);
  vec3 radiance = texelFetch(composed_radiance, source, 0).rgb;
  float exposure = texelFetch(frame_statistics, ivec2(0, 0), 0).x;
  out_colour = vec4(srgb_encode(filmic_tonemap(radiance * exposure)), 1.0);
}
