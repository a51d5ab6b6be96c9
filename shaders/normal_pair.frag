#version 450 core
// Both G-buffer layers' encoded normals side by side, layer 0 in RG and layer
// 1 in BA, for the march (ao_march.glsl), the thick spiral
// (ao_spiral_thick.glsl) and the solid angle (ao_solid_angle.glsl): their
// steps and taps read the normals of both
// layers at one pixel, and one fetch of this texture costs on llvmpipe about
// what one fetch of a layer of the G-buffer costs, where those two fetches
// were more than a third of the thick spiral's pass and over a quarter of
// the march's (docs/ao-accuracy.md, the thick spiral's cost). A copy: the
// same halves.
// A fragment shader, not a step of depth_pyramid.comp: llvmpipe writes a
// compute shader's image stores lane by lane, and the copy there cost more
// than it saved.

// Bindings are this shader's own; normal_pair_pass.cpp binds the same numbers.
layout(binding = 0) uniform sampler2DArray gbuffer_normal;

layout(location = 0) out vec4 out_normals;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  out_normals = vec4(texelFetch(gbuffer_normal, ivec3(pixel, 0), 0).xy,
                     texelFetch(gbuffer_normal, ivec3(pixel, 1), 0).xy);
}
