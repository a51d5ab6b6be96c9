// Each pass's own parameter block, shared by its host file and its shader as
// shared_constants.h is: the common subset of C++ and GLSL, every member a
// 4-byte scalar and every struct a whole number of 16-byte rows, so std140
// lays it out exactly as C++ does (static_asserts in shader_shared.hpp). A
// pass uploads its block and binds it at DEEPGI_UBO_PASS before it draws; a
// shader declares `layout(std140, binding = DEEPGI_UBO_PASS) uniform
// SaoBlock { SaoParameters sao; };` and reads named fields.
#ifndef DEEPGI_PASS_PARAMETERS_H
#define DEEPGI_PASS_PARAMETERS_H

// Deep SAO (sao.frag).
struct SaoParameters {
  float radius;     // world-space gather radius r (m)
  float bias;       // beta (m)
  float intensity;  // exponent on the visibility
  float q;          // screen-space radius (px) at which taps move one MIP level down

  int max_mip;      // deepest depth-pyramid level a tap may read
  int slices;       // gtao and bitmask: screen-space slices per pixel
  float thickness;  // march, spiral-thick, bitmask: solid depth (m) behind a stored surface
  int steps;        // gtao and bitmask: samples per slice side
};

// The deep radiosity gather (radiosity.frag).
struct RadiosityGatherParameters {
  float radius;     // world-space gather radius (m)
  float tap_clamp;  // largest contribution of one sample, per channel
  float q;          // px: the tap distance at which taps move one MIP level down
  int max_mip;      // deepest level of the prepared radiance the taps may read

  int layers;  // 1 or 2 layers gathered
  int method;  // DEEPGI_RADIOSITY_METHOD_*
  int visibility_steps;        // points marched from X to each sample (0: no visibility test)
  float visibility_thickness;  // m of solid behind a stored surface with no back face
};

// The radiosity prepare pass (radiosity_prepare.comp).
struct RadiosityPrepareParameters {
  float boost;     // 0: boost(rho) = 1; 1: the saturation boost
  float rho_prop;  // share of last frame's indirect light fed into this gather
  float prefilter;  // 1: a coarse texel's radiance is its surface's mean; 0: its one pixel's
  float unused0;
};

// The bilateral blur (bilateral_blur.frag); docs/deep-sao.md, "bilateral blur".
struct BlurParameters {
  float depth_tolerance;  // depth difference, as a fraction of the centre's, that weighs nothing
  float normal_power;     // weight * max(dot(n_tap, n_centre), 0)^power
  float plane_tolerance;  // distance from the centre's tangent plane, the same fraction
  float world_extent;     // m from the centre at which a tap weighs nothing (0: no limit)

  // The second source's (radiosity E's) reach while a still camera's history
  // is short: max(world_extent, second_extent_start / n) after
  // n = temporal_frame + 1 frames (docs/radiosity.md, "The blur"); 0: the
  // second source shares world_extent.
  float second_extent_start;
  float unused0;
  float unused1;
  float unused2;
};

// The anti-aliasing after the tonemap (antialias.frag).
struct AntialiasParameters {
  float edge_threshold;      // local luma range, as a fraction of its highest luma, below which
                             // a pixel is left alone
  float edge_threshold_min;  // and an absolute floor for dark regions (sRGB-encoded luma)
  float subpixel;            // strength of the sub-pixel blend, 0 to 1
  float unused0;
};

// Mirror reflections (reflection.frag); docs/reflections.md.
struct ReflectionParameters {
  float distance;   // m a reflected ray is marched
  int steps;        // samples along it
  int layers;       // 1 or 2 layers marched against
  float thickness;  // m of solid behind a surface with no back face

  int max_level;   // deepest level of the nearest-depth pyramid
  int skip_steps;  // samples one long step may skip
  int unused0;     // the radiosity and environment terms are the frame's
  int unused1;     // (FrameConstants: radiosity_term, environment_term)

  float edge_fade_pixels;   // hits this close to the buffer's edge fade out
  float facing_fade_start;  // camera-space z of the ray direction where fading starts
  float facing_fade_end;    // ... and where the hit is gone
  float unused2;            // std140 pads the block to whole vec4s
};
#endif
