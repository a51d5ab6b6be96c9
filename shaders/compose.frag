#version 450 core
// Outgoing radiance of layer 0: direct + emissive + a constant fill. The deep
// SAO and radiosity issues replace the constant fill with albedo * E * AV.
#include "frame_constants.glsl"
#include "gbuffer_encoding.glsl"

layout(binding = DEEPGI_UNIT_DIRECT_LIGHT) uniform sampler2DArray direct_light;
layout(binding = DEEPGI_UNIT_GBUFFER_ALBEDO) uniform sampler2DArray gbuffer_albedo;
layout(binding = DEEPGI_UNIT_GBUFFER_EMISSIVE) uniform sampler2DArray gbuffer_emissive;
layout(binding = DEEPGI_UNIT_GBUFFER_DEPTH) uniform sampler2DArray gbuffer_depth;
layout(binding = DEEPGI_UNIT_AO) uniform sampler2D ambient_visibility;  // blurred deep SAO

layout(location = 0) out vec3 out_radiance;

void main() {
  ivec3 texel = ivec3(gl_FragCoord.xy, 0);
  if (texelFetch(gbuffer_depth, texel, 0).r <= 0.0) {
    out_radiance = frame.background.rgb;
    return;
  }
  vec3 albedo = srgb_decode(texelFetch(gbuffer_albedo, texel, 0).rgb);
  out_radiance = texelFetch(direct_light, texel, 0).rgb + texelFetch(gbuffer_emissive, texel, 0).rgb +
                 frame.ambient.rgb * albedo * texelFetch(ambient_visibility, texel.xy, 0).r;
}
