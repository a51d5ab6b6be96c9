// Shared by the C++ host code (runtime/src/shader_shared.hpp) and the GLSL
// passes, so the uniform block binding points, vertex and G-buffer locations,
// enum values and the per-frame uniform block have one definition. Texture
// and image bindings are not here: each shader declares its own, and its
// pass's .cpp names the same numbers. Written in the common subset of both
// languages: #define, #include of another such file, and a struct laid out so
// that std140 equals the C++ layout (checked by static_assert in
// shader_shared.hpp). The C++ side provides mat4/vec4/ivec4 before including
// this file.
#ifndef DEEPGI_SHARED_CONSTANTS_H
#define DEEPGI_SHARED_CONSTANTS_H

#include "shared_enums.h"

// Uniform block binding points.
#define DEEPGI_UBO_FRAME 0
#define DEEPGI_UBO_PASS 1  // the running pass's own block (pass_parameters.h)

// Vertex attribute locations.
#define DEEPGI_ATTRIBUTE_POSITION 0
#define DEEPGI_ATTRIBUTE_NORMAL 1
#define DEEPGI_ATTRIBUTE_UV 2
#define DEEPGI_ATTRIBUTE_COLOUR 3  // linear RGBA multiplying the base colour

// G-buffer fragment outputs (colour attachment index).
#define DEEPGI_GBUFFER_OUTPUT_NORMAL 0
#define DEEPGI_GBUFFER_OUTPUT_ALBEDO 1
#define DEEPGI_GBUFFER_OUTPUT_EMISSIVE 2
#define DEEPGI_GBUFFER_OUTPUT_MOTION 3

// Explicit uniform locations of the material values draw_scene sets (a
// pass's own uniforms have locations its shader and .cpp choose).
#define DEEPGI_UNIFORM_BASE_COLOUR_FACTOR 0
#define DEEPGI_UNIFORM_EMISSIVE_FACTOR 1
#define DEEPGI_UNIFORM_HAS_BASE_COLOUR_TEXTURE 2
#define DEEPGI_UNIFORM_HAS_EMISSIVE_TEXTURE 5  // int
#define DEEPGI_UNIFORM_ALPHA_CUTOFF 6          // float: alpha below it is a hole; < 0 opaque
#define DEEPGI_UNIFORM_MATERIAL_SURFACE 7      // vec2: glTF roughness and metallic factors
#define DEEPGI_UNIFORM_MIRROR_ROUGHNESS 8      // float: roughness at or below which a metal is a mirror

// Scalars are named fields, four to a 16-byte row, so std140 packs them
// exactly as C++ does; the padding is explicit.
struct FrameConstants {
  mat4 view;
  mat4 projection;  // guard-banded, reversed Z, infinite far plane
  mat4 previous_view;
  mat4 previous_view_projection;
  mat4 camera_to_light_clip;  // camera space -> shadow map clip space
  vec4 camera_ray_scale;      // (1/P00, 1/P11, near plane, 0): position from linear depth
  vec4 light_vector;          // camera space; directional: unit vector to the light; spot, point:
                              // position, w: 1 / range (0: unlimited)
  vec4 spot_axis;             // camera space spot direction; w: cos of the outer cone;
                              // point: (near, far) of the shadow cube's faces
  vec4 light_radiance;        // rgb: colour * intensity; w: cos of the inner cone
  vec4 ambient;               // rgb: constant fill radiance factor (times albedo)
  vec4 background;            // rgb: radiance where nothing is hit
  vec4 internal_size;         // (w, h, 1/w, 1/h) of the guard-banded buffers

  float min_separation;        // m, layer 1 behind layer 0
  float exposure;              // the setting; -1: auto (frame_statistics.comp measures it)
  float shadow_normal_offset;  // m along the normal before the shadow lookup
  int rotation_seed;           // picks the per-pixel rotation field (pixel_rotation_hash.h); 0: shipped

  int guard_band;       // px on every side
  int viewport_width;   // px
  int viewport_height;  // px
  int generator;        // DEEPGI_GENERATOR_*

  int light_kind;  // DEEPGI_LIGHT_*
  int debug_view;  // DEEPGI_VIEW_*
  int temporal_frame;    // frames since history was invalidated (0 on the first)
  float temporal_angle;  // rad, 2 pi temporal_sample.x: this frame's extra rotation of the gather patterns

  // xy: this frame's point (u, v) of the Sobol sequence in [0, 1)^2 (temporal_sequence.h);
  // z: the radiosity taps' radial shift frac(1/2 + v) - 1/2 in [-1/2, 1/2),
  // 0 on the first frame; w: 0.
  vec4 temporal_sample;

  // 1: compose adds the term, 0: leaves it out (--no-ao, --no-radiosity,
  // --no-environment; reflection: the reflection pass runs this frame, which
  // debug_view's reflection hit view also reads).
  int ao_term;
  int radiosity_term;
  int environment_term;
  int reflection_term;

  // The next frame's view and guard-banded projection: the delay generator's
  // given camera, the predict generator's extrapolated one (this frame's
  // camera for the other generators, which do not read them). Kept apart, as
  // view and projection are, so that the third layer's positions are computed
  // as the next frame's layer 0 will be, to the bit.
  mat4 next_view;
  mat4 next_projection;
};

#endif
