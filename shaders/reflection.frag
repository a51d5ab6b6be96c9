#version 450 core
// Mirror reflections through both deep G-buffer layers (the deep G-buffer
// paper's section 4.5; docs/reflections.md). Variants (reflection_pass.cpp):
//   NEAREST_BASE    level 0 of the pass's nearest-depth pyramid: layer 0's
//                   linear depth, a huge value where nothing is stored
//   NEAREST_REDUCE  level m+1 from level m (bound as an image): the minimum
//                   of the texels it covers
//   none            the march: one reflected ray per mirror pixel
//
// The march. From a mirror pixel's layer-0 point X with normal n, the ray
// leaves along r = reflect(normalize(X), n) in camera space and is sampled at
// t_k = (k + u) * D / N, k = 0 .. N-1, where D is the march distance, N the
// step count and u the pixel's jitter (a hash of the pixel, advanced by a
// frame offset). A sample q projected to pixel p is inside layer L's solid
// when
//   - it lies behind the depth stored at p in layer L,
//   - in front of where that solid ends: the nearest back face behind the
//     layer (backface_depth pass), at least two steps deep; behind an open
//     mesh (no back face) `thickness` deep,
//   - and behind that surface's plane by more than 1 mm per metre of depth,
//     so that the mirror itself and surfaces the ray grazes are not hit.
// The first inside sample ends the ray; layer 0 is tested before layer 1. A
// sample off the guard-banded buffer or in front of the near plane ends it
// too: nothing is known there, and the environment stands in.
//
// Long steps. Before testing sample k one by one, the march asks whether the
// next `skip_steps` samples can hit anything at all: the samples lie on one
// segment whose projection stays within the bounding box of its projected
// ends (one pixel of margin), and its depth is largest at one of its ends.
// When that depth is in front of the nearest layer-0 depth anywhere in the
// box (the nearest-depth pyramid, at the level where the box spans at most
// 2x2 texels), no sample can be behind any layer, and all of them are
// skipped. So the long steps never change which sample hits: a CPU march of
// every sample gives the same answer (tests/runtime/reflection_test.cpp).
//
// A hit takes the lit radiance of the hit texel in the layer hit: its direct
// light, its emission (layer 0) and albedo / pi times the deep radiosity E of
// that layer with the environment filling the uncovered part, as compose.frag
// does (without the AO, which exists for layer 0 only). A hit on a mirror
// texel is followed by a second march from there (hit_radiance). The hit fades into
// the environment towards the buffer's edge, for rays pointing at the camera
// and over the last tenth of the distance, so no seam shows.
#include "frame_constants.glsl"
#include "pass_parameters.h"
#include "gbuffer_encoding.glsl"
#include "math_constants.glsl"

layout(std140, binding = DEEPGI_UBO_PASS) uniform ReflectionBlock {
  ReflectionParameters reflection;
};

#if defined(NEAREST_BASE)

layout(binding = 4) uniform sampler2DArray gbuffer_depth;
layout(location = 0) out float out_nearest;

void main() {
  float stored = texelFetch(gbuffer_depth, ivec3(gl_FragCoord.xy, 0), 0).r;
  out_nearest = stored > 0.0 ? frame.camera_ray_scale.z / stored : 3.0e38;
}

#elif defined(NEAREST_REDUCE)

layout(binding = 0, r32f) uniform readonly image2D finer;
layout(location = 0) out float out_nearest;

void main() {
  // Levels are floor-sized: the last texel of a row or column also covers
  // the finer level's odd last texel, so every texel of level 0 has a
  // covering texel at every level (min(x >> m, size - 1)).
  ivec2 size = imageSize(finer);
  ivec2 first = 2 * ivec2(gl_FragCoord.xy);
  ivec2 last = first + 1;
  ivec2 coarse_size = max(size / 2, ivec2(1));
  if (int(gl_FragCoord.x) == coarse_size.x - 1) last.x = size.x - 1;
  if (int(gl_FragCoord.y) == coarse_size.y - 1) last.y = size.y - 1;
  last = min(last, size - 1);
  float nearest = 3.0e38;
  for (int y = first.y; y <= last.y; ++y)
    for (int x = first.x; x <= last.x; ++x) nearest = min(nearest, imageLoad(finer, ivec2(x, y)).r);
  out_nearest = nearest;
}

#else

#include "environment.glsl"
#include "pixel_rotation.glsl"

// Bindings local to this pass; reflection_pass.cpp declares the same numbers.
layout(binding = 0) uniform sampler2DArray gbuffer_normal;
layout(binding = 1) uniform sampler2DArray gbuffer_albedo;
layout(binding = 2) uniform sampler2DArray gbuffer_emissive;
layout(binding = 3) uniform sampler2D irradiance_layer0;  // deep radiosity E (rgb), confidence (a)
layout(binding = 4) uniform sampler2DArray gbuffer_depth;
layout(binding = 5) uniform sampler2D irradiance_layer1;
layout(binding = 6) uniform sampler2DArray direct_light;
layout(binding = 7) uniform sampler2DArray backface_depth;  // reversed Z; 0: no back face
layout(binding = 8) uniform sampler2D nearest_depth;        // this pass's pyramid

// rgb: reflected radiance (environment where nothing was hit); a: the hit's weight.
layout(location = 0) out vec4 out_radiance;
// xy: the hit texel's centre, z: the layer hit (-1: none, -2: not a mirror), w: the jitter u.
layout(location = 1) out vec4 out_hit;

const int march_stop = -2;  // off the buffer or in front of the near plane
const int march_empty = -1;

vec2 pixel_of(vec3 q) {
  return (q.xy / (-q.z * frame.camera_ray_scale.xy) * 0.5 + 0.5) * frame.internal_size.xy;
}

bool on_buffer(vec3 q, vec2 at) {
  return -q.z > frame.camera_ray_scale.z && all(greaterThanEqual(at, vec2(0.0))) &&
         all(lessThan(at, frame.internal_size.xy));
}

// Whether layer `layer`'s solid at pixel p contains q, at linear depth z.
bool solid_contains(vec3 q, ivec2 p, int layer, float z, float step_length) {
  float near_plane = frame.camera_ray_scale.z;
  float stored = texelFetch(gbuffer_depth, ivec3(p, layer), 0).r;
  if (stored <= 0.0) return false;
  float depth = near_plane / stored;
  if (z <= depth) return false;
  float back_face = texelFetch(backface_depth, ivec3(p, layer), 0).r;
  float solid_end = back_face > 0.0 ? max(near_plane / back_face, depth + 2.0 * step_length)
                                    : depth + reflection.thickness;
  if (z >= solid_end) return false;
  vec3 surface = camera_position_at(vec2(p) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
  vec3 surface_normal = decode_normal(texelFetch(gbuffer_normal, ivec3(p, layer), 0).xy);
  return dot(q - surface, surface_normal) < -1.0e-3 * z;
}

// Which layer's solid contains q (march_empty: none), or march_stop. One
// call per layer rather than a loop over the layers, as the gathers do
// (llvmpipe keeps such a loop a loop, selecting on the layer at run time).
int inside_layer(vec3 q, float step_length, out ivec2 p) {
  vec2 at = pixel_of(q);
  p = ivec2(0);
  if (!on_buffer(q, at)) return march_stop;
  p = ivec2(at);
  float z = -q.z;
  if (solid_contains(q, p, 0, z, step_length)) return 0;
  if (reflection.layers > 1 && solid_contains(q, p, 1, z, step_length)) return 1;
  return march_empty;
}

// Whether no sample between q_a and q_b (both on the buffer) can be inside
// any layer: both in front of the nearest layer-0 depth over their box.
bool segment_in_front(vec3 qa, vec3 qb) {
  vec2 at_a = pixel_of(qa), at_b = pixel_of(qb);
  if (!on_buffer(qa, at_a) || !on_buffer(qb, at_b)) return false;
  ivec2 size = ivec2(frame.internal_size.xy);
  ivec2 lo = clamp(ivec2(floor(min(at_a, at_b))) - 1, ivec2(0), size - 1);
  ivec2 hi = clamp(ivec2(floor(max(at_a, at_b))) + 1, ivec2(0), size - 1);
  int level = 0;
  while (level <= reflection.max_level &&
         any(greaterThan((hi >> level) - (lo >> level), ivec2(1))))
    ++level;
  if (level > reflection.max_level) return false;
  // GL's floor-sized levels, computed rather than asked for: llvmpipe's
  // textureSize answered with the next level's size here.
  ivec2 level_size = max(size >> level, ivec2(1));
  ivec2 a = min(lo >> level, level_size - 1), b = min(hi >> level, level_size - 1);
  float nearest = min(min(texelFetch(nearest_depth, a, level).r, texelFetch(nearest_depth, ivec2(b.x, a.y), level).r),
                      min(texelFetch(nearest_depth, ivec2(a.x, b.y), level).r, texelFetch(nearest_depth, b, level).r));
  return max(-qa.z, -qb.z) * 1.00001 < nearest;
}

vec3 environment_radiance(vec3 camera_direction) {
  if (frame.environment_term == 0) return vec3(0.0);
  return environment_irradiance(normalize(transpose(mat3(frame.view)) * camera_direction)) * inv_pi;
}

vec3 lit_radiance(ivec2 p, int layer) {
  ivec3 texel = ivec3(p, layer);
  vec3 albedo = srgb_decode(texelFetch(gbuffer_albedo, texel, 0).rgb);
  vec3 normal = decode_normal(texelFetch(gbuffer_normal, texel, 0).xy);
  vec4 gathered = vec4(0.0);
  if (frame.radiosity_term != 0)
    gathered = layer == 0 ? texelFetch(irradiance_layer0, p, 0) : texelFetch(irradiance_layer1, p, 0);
  float confidence = clamp(gathered.a, 0.0, 1.0);
  vec3 environment = frame.environment_term != 0
                         ? environment_irradiance(normalize(transpose(mat3(frame.view)) * normal))
                         : vec3(0.0);
  vec3 emissive = layer == 0 ? texelFetch(gbuffer_emissive, texel, 0).rgb : vec3(0.0);
  return texelFetch(direct_light, texel, 0).rgb + emissive +
         albedo * inv_pi * (gathered.rgb + environment * (1.0 - confidence));
}

// Marches the ray origin + t direction (camera space) with the pixel's
// jitter; the layer hit (march_empty: none) and its texel and t.
int march(vec3 origin, vec3 direction, float jitter, out ivec2 hit_pixel, out float hit_t) {
  float step_length = reflection.distance / float(reflection.steps);
  hit_pixel = ivec2(0);
  hit_t = 0.0;
  int k = 0;
  while (k < reflection.steps) {
    int span = min(reflection.skip_steps, reflection.steps - k);
    if (span > 1 && segment_in_front(origin + direction * ((float(k) + jitter) * step_length),
                                     origin + direction * ((float(k + span - 1) + jitter) * step_length))) {
      k += span;
      continue;
    }
    float t = (float(k) + jitter) * step_length;
    ivec2 p;
    int layer = inside_layer(origin + direction * t, step_length, p);
    if (layer == march_stop) return march_empty;
    if (layer >= 0) {
      hit_pixel = p;
      hit_t = t;
      return layer;
    }
    ++k;
  }
  return march_empty;
}

// The fades of a hit: towards the buffer's edge, for rays pointing at the
// camera, and over the last tenth of the distance.
float hit_weight(ivec2 hit_pixel, vec3 direction, float hit_t) {
  vec2 centre = vec2(hit_pixel) + 0.5;
  vec2 edge = min(centre, frame.internal_size.xy - centre);
  float weight = clamp(min(edge.x, edge.y) / reflection.edge_fade_pixels, 0.0, 1.0);
  weight *= 1.0 - smoothstep(reflection.facing_fade_start, reflection.facing_fade_end, direction.z);
  weight *= 1.0 - smoothstep(0.9, 1.0, hit_t / reflection.distance);
  return weight;
}

// What a ray arriving along `direction` at the hit texel sees there. A
// diffuse texel sends its lit radiance. A mirror texel sends its emission
// plus its reflectance times what its own reflection brings: the ray is
// marched once more from the texel's point, reflected about its normal, and
// what that march hits is shaded as lit radiance (a third mirror as diffuse).
vec3 hit_radiance(ivec2 hit_pixel, int hit_layer, vec3 direction, float jitter) {
  ivec3 texel = ivec3(hit_pixel, hit_layer);
  vec4 albedo = texelFetch(gbuffer_albedo, texel, 0);
  if (!is_mirror_alpha(albedo.a)) return lit_radiance(hit_pixel, hit_layer);
  float depth = frame.camera_ray_scale.z / texelFetch(gbuffer_depth, texel, 0).r;
  vec3 origin = camera_position_at(vec2(hit_pixel) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
  vec3 normal = decode_normal(texelFetch(gbuffer_normal, texel, 0).xy);
  vec3 next = normalize(reflect(direction, normal));
  ivec2 next_pixel;
  float next_t;
  int next_layer = march(origin, next, jitter, next_pixel, next_t);
  vec3 seen = environment_radiance(next);
  if (next_layer >= 0)
    seen = mix(seen, lit_radiance(next_pixel, next_layer), hit_weight(next_pixel, next, next_t));
  vec3 emissive = hit_layer == 0 ? texelFetch(gbuffer_emissive, texel, 0).rgb : vec3(0.0);
  return emissive + srgb_decode(albedo.rgb) * seen;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float stored = texelFetch(gbuffer_depth, ivec3(pixel, 0), 0).r;
  if (stored <= 0.0 || !is_mirror_alpha(texelFetch(gbuffer_albedo, ivec3(pixel, 0), 0).a)) {
    out_radiance = vec4(0.0);
    out_hit = vec4(0.0, 0.0, -2.0, 0.0);
    return;
  }
  float depth = frame.camera_ray_scale.z / stored;
  vec3 origin = camera_position_at(vec2(pixel) + 0.5, depth, frame.internal_size, frame.camera_ray_scale);
  vec3 normal = decode_normal(texelFetch(gbuffer_normal, ivec3(pixel, 0), 0).xy);
  vec3 direction = normalize(reflect(normalize(origin), normal));
  float jitter = fract(float(avalanche32(pixel_rotation_hash(uvec2(pixel), uint(frame.rotation_seed)) ^ 0x3c6ef372u) >> 8u) * (1.0 / 16777216.0) +
                       frame.temporal_sample.y);

  ivec2 hit_pixel;
  float hit_t;
  int hit_layer = march(origin, direction, jitter, hit_pixel, hit_t);
  vec3 environment = environment_radiance(direction);
  if (hit_layer < 0) {
    out_radiance = vec4(environment, 0.0);
    out_hit = vec4(-1.0, -1.0, -1.0, jitter);
    return;
  }
  float weight = hit_weight(hit_pixel, direction, hit_t);
  out_radiance = vec4(mix(environment, hit_radiance(hit_pixel, hit_layer, direction, jitter), weight), weight);
  out_hit = vec4(vec2(hit_pixel) + 0.5, float(hit_layer), jitter);
}

#endif
