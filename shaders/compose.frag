#version 450 core
// Outgoing radiance of layer 0 (docs/design.md, section 5.11):
//
//   L = direct + albedo/pi * (E + env(n) * (1 - c)) * AV + emissive
//
// E is the blurred deep radiosity irradiance and c its confidence. With the
// area estimator (radiosity.frag) E already counts only the part of the
// hemisphere its samples covered and c is that covered share, so E is not
// scaled by c: the environment fills the uncovered rest (open sky, the
// buffer's edge). The deep G-buffer paper scales E by c; this code does not, and the
// published normalisation (kept for comparison) is composed the same way,
// without the scaling. The environment is an
// analytic sky for scenes with a sky (background not black) and the constant
// ambient otherwise. Both are irradiance, so the Lambertian 1/pi turns them
// into radiance.
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"

// Bindings are this shader's own; compose_pass.cpp binds the same numbers.
layout(binding = 7) uniform sampler2DArray direct_light;
layout(binding = 0) uniform sampler2DArray gbuffer_normal;
layout(binding = 1) uniform sampler2DArray gbuffer_albedo;
layout(binding = 2) uniform sampler2DArray gbuffer_emissive;
layout(binding = 4) uniform sampler2DArray gbuffer_depth;
layout(binding = 11) uniform sampler2D ambient_visibility;  // blurred deep SAO, signed
layout(binding = 14) uniform sampler2D radiosity;    // blurred E (rgb), confidence (a)

layout(location = 0) out vec3 out_radiance;

#include "math_constants.glsl"
#include "environment.glsl"

// Mirror reflections (reflection.frag, filtered by reflection_temporal.frag),
// bound only while those passes run: a
// mirror pixel is its reflectance (albedo) times the reflected radiance, plus
// its emission; a polished metal has no diffuse term.
layout(binding = 3) uniform sampler2D reflection_radiance;

void main() {
  ivec3 texel = ivec3(gl_FragCoord.xy, 0);
  if (texelFetch(gbuffer_depth, texel, 0).r <= 0.0) {
    out_radiance = frame.background.rgb;
    return;
  }
  vec4 albedo_and_flag = texelFetch(gbuffer_albedo, texel, 0);
  vec3 albedo = srgb_decode(albedo_and_flag.rgb);
  if (frame.reflection_term != 0 && is_mirror_alpha(albedo_and_flag.a)) {
    out_radiance = texelFetch(gbuffer_emissive, texel, 0).rgb +
                   albedo * texelFetch(reflection_radiance, texel.xy, 0).rgb;
    return;
  }
  vec3 normal = decode_normal(texelFetch(gbuffer_normal, texel, 0).xy);
  vec3 world_normal = normalize(transpose(mat3(frame.view)) * normal);
  vec4 gathered = frame.radiosity_term != 0 ? texelFetch(radiosity, texel.xy, 0) : vec4(0.0);
  float confidence = clamp(gathered.a, 0.0, 1.0);
  vec3 environment = frame.environment_term != 0 ? environment_irradiance(world_normal) : vec3(0.0);
  vec3 irradiance = gathered.rgb + environment * (1.0 - confidence);
  // The solid-angle AV arrives signed (sao.frag): the clamp is applied here,
  // after the blur and the temporal filter have averaged its noise.
  float visibility = frame.ao_term != 0 ? clamp(texelFetch(ambient_visibility, texel.xy, 0).r, 0.0, 1.0) : 1.0;
  out_radiance = texelFetch(direct_light, texel, 0).rgb + texelFetch(gbuffer_emissive, texel, 0).rgb +
                 albedo / pi * irradiance * visibility;
}
