#version 450 core
// Post-process anti-aliasing of the displayed image, after the tonemap (so
// the AO and irradiance the tests read are untouched). In the manner of
// FXAA: where the local luma contrast is high enough to be an edge, find the
// edge's orientation, walk along it to its ends, and blend the pixel with its
// neighbour across the edge by how far it lies from the nearer end (the
// staircase of a tilted edge becomes a ramp); a separate sub-pixel term
// softens features smaller than a pixel. Works on the sRGB-encoded values,
// which are close to perceptual, as the contrast test wants.
#include "frame_constants.glsl"
#include "pass_parameters.h"

// Local bindings of this pass (antialias_pass.cpp uses the same numbers).
layout(binding = 0) uniform sampler2D tonemapped;
layout(std140, binding = DEEPGI_UBO_PASS) uniform AntialiasBlock {
  AntialiasParameters antialias;
};

layout(location = 0) out vec4 out_colour;

// Longest walk along an edge, in pixels each way.
const int max_steps = 12;

vec3 colour_at(ivec2 p) {
  return texelFetch(tonemapped, clamp(p, ivec2(0), textureSize(tonemapped, 0) - 1), 0).rgb;
}
float luma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }
float luma_at(ivec2 p) { return luma(colour_at(p)); }

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec3 centre = colour_at(p);
  float l_c = luma(centre);
  float l_n = luma_at(p + ivec2(0, 1)), l_s = luma_at(p + ivec2(0, -1));
  float l_e = luma_at(p + ivec2(1, 0)), l_w = luma_at(p + ivec2(-1, 0));
  float lowest = min(l_c, min(min(l_n, l_s), min(l_e, l_w)));
  float highest = max(l_c, max(max(l_n, l_s), max(l_e, l_w)));
  float range = highest - lowest;
  // Flat or low-contrast: left exactly as it is.
  if (range < max(antialias.edge_threshold_min, antialias.edge_threshold * highest)) {
    out_colour = vec4(centre, 1.0);
    return;
  }
  float l_ne = luma_at(p + ivec2(1, 1)), l_nw = luma_at(p + ivec2(-1, 1));
  float l_se = luma_at(p + ivec2(1, -1)), l_sw = luma_at(p + ivec2(-1, -1));

  // An edge running horizontally changes luma vertically, and vice versa.
  float change_vertically = 2.0 * abs(l_n + l_s - 2.0 * l_c) + abs(l_ne + l_se - 2.0 * l_e) +
                            abs(l_nw + l_sw - 2.0 * l_w);
  float change_horizontally = 2.0 * abs(l_e + l_w - 2.0 * l_c) + abs(l_ne + l_nw - 2.0 * l_n) +
                              abs(l_se + l_sw - 2.0 * l_s);
  bool horizontal_edge = change_vertically >= change_horizontally;
  float l_pos = horizontal_edge ? l_n : l_e;
  float l_neg = horizontal_edge ? l_s : l_w;
  bool toward_pos = abs(l_pos - l_c) >= abs(l_neg - l_c);
  float l_across = toward_pos ? l_pos : l_neg;
  ivec2 across = horizontal_edge ? ivec2(0, toward_pos ? 1 : -1) : ivec2(toward_pos ? 1 : -1, 0);
  ivec2 along = horizontal_edge ? ivec2(1, 0) : ivec2(0, 1);

  // Walk both ways while the pair (pixel, its neighbour across) still looks
  // like this edge: their mean stays within a quarter of the gradient.
  float edge_mean = 0.5 * (l_c + l_across);
  float tolerance = 0.25 * abs(l_across - l_c);
  int steps_neg = max_steps + 1, steps_pos = max_steps + 1;
  float end_neg = edge_mean, end_pos = edge_mean;
  for (int i = 1; i <= max_steps; ++i) {
    if (steps_neg > max_steps) {
      ivec2 q = p - along * i;
      float m = 0.5 * (luma_at(q) + luma_at(q + across));
      if (abs(m - edge_mean) >= tolerance) { steps_neg = i; end_neg = m; }
    }
    if (steps_pos > max_steps) {
      ivec2 q = p + along * i;
      float m = 0.5 * (luma_at(q) + luma_at(q + across));
      if (abs(m - edge_mean) >= tolerance) { steps_pos = i; end_pos = m; }
    }
  }
  // Blend only toward the end where the staircase steps the way that makes
  // this pixel belong partly to the other side.
  bool nearer_neg = steps_neg < steps_pos;
  float end = nearer_neg ? end_neg : end_pos;
  float nearer = float(min(steps_neg, steps_pos));
  float span = float(steps_neg + steps_pos) - 1.0;
  bool steps_our_way = (end - edge_mean < 0.0) != (l_c - edge_mean < 0.0);
  float edge_blend = steps_our_way ? 0.5 - (nearer - 0.5) / span : 0.0;

  // Sub-pixel features: how far the centre stands out from its 3x3 mean.
  float mean = (2.0 * (l_n + l_s + l_e + l_w) + (l_ne + l_nw + l_se + l_sw)) / 12.0;
  float standing_out = clamp(abs(mean - l_c) / range, 0.0, 1.0);
  float smooth_out = (3.0 - 2.0 * standing_out) * standing_out * standing_out;
  float subpixel_blend = smooth_out * smooth_out * antialias.subpixel;

  float blend = clamp(max(edge_blend, subpixel_blend), 0.0, 0.5);
  out_colour = vec4(mix(centre, colour_at(p + across), blend), 1.0);
}
