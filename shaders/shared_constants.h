// Shared by the C++ host code (runtime/src/shader_shared.hpp) and the GLSL
// passes, so binding points, enum values and the per-frame uniform block have
// one definition. Written in the common subset of both languages: #define,
// #include of another such file, and a struct laid out so that std140 equals
// the C++ layout (checked by static_assert in shader_shared.hpp). The C++
// side provides mat4/vec4/ivec4 before including this file.
#ifndef DEEPGI_SHARED_CONSTANTS_H
#define DEEPGI_SHARED_CONSTANTS_H

#include "shared_enums.h"

// Uniform block binding points.
#define DEEPGI_UBO_FRAME 0
#define DEEPGI_UBO_PASS 1  // the running pass's own block (pass_parameters.h)

// Texture units (sampler bindings).
#define DEEPGI_UNIT_GBUFFER_NORMAL 0
#define DEEPGI_UNIT_GBUFFER_ALBEDO 1
#define DEEPGI_UNIT_GBUFFER_EMISSIVE 2
#define DEEPGI_UNIT_GBUFFER_MOTION 3
#define DEEPGI_UNIT_GBUFFER_DEPTH 4
#define DEEPGI_UNIT_REFERENCE_DEPTH 5  // layer-0 depth the second layer compares against
#define DEEPGI_UNIT_SHADOW_MAP 6
#define DEEPGI_UNIT_DIRECT_LIGHT 7
#define DEEPGI_UNIT_COMPOSE 8
#define DEEPGI_UNIT_BASE_COLOUR 9
#define DEEPGI_UNIT_DEPTH_PYRAMID 10  // RG32F with MIPs: linear depth of layer 0 (R) and 1 (G); 0 = no surface
#define DEEPGI_UNIT_AO 11             // ambient visibility (R), raw or blurred
#define DEEPGI_UNIT_BLUR_SOURCE 12    // whatever the bilateral blur is smoothing
#define DEEPGI_UNIT_AO_RAW 13         // debug view only
#define DEEPGI_UNIT_RADIOSITY 14      // RGBA16F: E (rgb) and confidence (a) of layer 0, blurred
#define DEEPGI_UNIT_RADIOSITY_PREVIOUS_LAYER0 15  // last frame's E of layer 0 (bounces)
#define DEEPGI_UNIT_RADIOSITY_PREVIOUS_LAYER1 16  // last frame's E of layer 1 (bounces)
#define DEEPGI_UNIT_RADIOSITY_RAW_LAYER0 17       // this frame's E of layer 0 (debug view)
#define DEEPGI_UNIT_RADIOSITY_RAW_LAYER1 18       // this frame's E of layer 1 (debug view)
#define DEEPGI_UNIT_RADIOSITY_HISTORY_KEY 19      // last frame's depth + normal key (temporal filter)
#define DEEPGI_UNIT_RADIOSITY_HISTORY_KEY_LAYER1 20  // the same for layer 1 (prepare pass)
#define DEEPGI_UNIT_RADIOSITY_RADIANCE 21  // RGBA16F array with MIPs: prepared outgoing radiance B per layer
#define DEEPGI_UNIT_RADIOSITY_NORMAL 22    // RG16F array with MIPs: prepared octahedral normal per layer
#define DEEPGI_UNIT_HISTORY_PARTIAL 23     // last frame's mean of the current rotation cycle (temporal filters)
#define DEEPGI_UNIT_EMISSIVE 24            // a material's emissive texture (sRGB)
#define DEEPGI_UNIT_BLUR_SECOND_SOURCE 25  // the bilateral blur's second signal, same weights
#define DEEPGI_UNIT_BLUR_KEY 26            // RGBA32F: layer-0 normal (xyz) and linear depth (w)
#define DEEPGI_UNIT_SHADOW_CUBE 27         // point light: depth cube map, one perspective face per axis
#define DEEPGI_UNIT_AO_TEMPORAL 28         // temporally filtered visibility (debug view)
#define DEEPGI_UNIT_BACKFACE_DEPTH 29      // DEPTH32F array, reversed Z: per layer, the nearest back face behind it (the march)

// Image units (compute shaders).
#define DEEPGI_IMAGE_PYRAMID_SOURCE 0
#define DEEPGI_IMAGE_PYRAMID_DESTINATION 1
#define DEEPGI_IMAGE_PREPARE_NORMAL_SOURCE 2
#define DEEPGI_IMAGE_PREPARE_NORMAL_DESTINATION 3

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

// Explicit uniform locations of per-draw and per-pass values.
#define DEEPGI_UNIFORM_BASE_COLOUR_FACTOR 0
#define DEEPGI_UNIFORM_EMISSIVE_FACTOR 1
#define DEEPGI_UNIFORM_HAS_BASE_COLOUR_TEXTURE 2
#define DEEPGI_UNIFORM_LIGHT_VIEW_PROJECTION 3
#define DEEPGI_UNIFORM_LAYER 4
#define DEEPGI_UNIFORM_HAS_EMISSIVE_TEXTURE 5  // int
#define DEEPGI_UNIFORM_ALPHA_CUTOFF 6          // float: alpha below it is a hole; < 0 opaque
#define DEEPGI_UNIFORM_MATERIAL_SURFACE 7      // vec2: glTF roughness and metallic factors
#define DEEPGI_UNIFORM_MIRROR_ROUGHNESS 8      // float: roughness at or below which a metal is a mirror
#define DEEPGI_UNIFORM_PYRAMID_LEVEL 20    // int: the MIP level being written
#define DEEPGI_UNIFORM_BLUR_DIRECTION 23   // ivec2: (1, 0) horizontal, (0, 1) vertical
#define DEEPGI_UNIFORM_RADIOSITY_ALPHA 29       // float: temporal blend weight of the history
#define DEEPGI_UNIFORM_RADIOSITY_TO_PREVIOUS 30 // mat4: camera space -> previous camera space
#define DEEPGI_UNIFORM_COMPOSE_TERMS 36         // ivec3: AO, radiosity, environment (0: left out)
#define DEEPGI_UNIFORM_COMPOSE_REFLECTIONS 37   // int: 1 while the reflection pass runs
#define DEEPGI_UNIFORM_BACKFACE_LAYER 39        // int: the G-buffer layer the back faces must lie behind

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
  float exposure;              // multiplier before the tonemap
  float shadow_normal_offset;  // m along the normal before the shadow lookup
  float depth_view_range;      // m, the depth debug view's white-to-black range

  int guard_band;       // px on every side
  int viewport_width;   // px
  int viewport_height;  // px
  int generator;        // DEEPGI_GENERATOR_*

  int light_kind;  // DEEPGI_LIGHT_*
  int debug_view;  // DEEPGI_VIEW_*
  int temporal_phase;    // frames since history was invalidated, modulo DEEPGI_TEMPORAL_CYCLE
  float temporal_angle;  // rad, this frame's extra rotation of the gather patterns (0 at phase 0)
};

#endif
