#version 450 core
// The example pass's shader (ao_complement_pass.cpp): one minus the blurred
// ambient visibility, the share of the hemisphere that is occluded.

// Bindings are this shader's own; ao_complement_pass.cpp binds the same numbers.
layout(binding = 0) uniform sampler2D ambient_visibility;  // "ao.blurred"

layout(location = 0) out vec4 out_occlusion;

void main() {
  float visibility = texelFetch(ambient_visibility, ivec2(gl_FragCoord.xy), 0).r;
  out_occlusion = vec4(1.0 - visibility, 0.0, 0.0, 1.0);
}
