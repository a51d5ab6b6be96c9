// Finding last frame's texel for this frame's surface point, shared by the
// temporal filters and the radiosity bounce. The G-buffer's motion vectors
// (gbuffer.frag: xy pixels moved, z linear depth in the previous camera) say
// where the point was; the history key written last frame at that texel (x:
// linear depth, yz: octahedral world-space normal, w: frames accumulated)
// says what was there. History is used only where both agree, so a pixel
// that was hidden or off screen (disocclusion, a cut) starts fresh.
//
// Needs frame_constants.glsl and gbuffer_encoding.glsl.

// Relative depth and normal agreement needed to keep history.
const float history_depth_tolerance = 0.05;
const float history_normal_cosine = 0.9;

// The view matrix is a rotation plus translation, so its transpose inverts
// the rotation.
vec3 world_normal_from_camera(vec3 camera_normal) { return transpose(mat3(frame.view)) * camera_normal; }

// The history key this frame writes for a surface point.
vec4 history_key_for(float linear_depth, vec3 camera_normal, float frames_accumulated) {
  return vec4(linear_depth, encode_normal(world_normal_from_camera(camera_normal)), frames_accumulated);
}

// True, with `texel` and `key` set, when last frame's history at the point
// seen at `pixel` of `layer` may be used.
bool find_history(ivec2 pixel, int layer, vec3 camera_normal, sampler2DArray motion_texture, sampler2D key_texture,
                  out ivec2 texel, out vec4 key) {
  texel = ivec2(-1);
  key = vec4(0.0);
  vec4 motion = texelFetch(motion_texture, ivec3(pixel, layer), 0);
  float expected_depth = motion.z;
  // A zero depth: the point was behind the previous camera. The magnitude
  // test also rejects infinities and NaN before they reach an int conversion.
  if (!(expected_depth > 0.0) || !all(lessThan(abs(motion.xy), vec2(65536.0)))) return false;
  texel = ivec2(floor(vec2(pixel) + 0.5 - motion.xy));
  if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(frame.internal_size.xy)))) return false;
  key = texelFetch(key_texture, texel, 0);
  if (!(key.x > 0.0) || abs(key.x - expected_depth) > history_depth_tolerance * expected_depth) return false;
  return dot(decode_normal(key.yz), world_normal_from_camera(camera_normal)) >= history_normal_cosine;
}

// True where the point has not moved on screen since last frame (the motion
// vector below 1/64 pixel): its history is the same point seen the same way,
// so the temporal filters may average every frame (temporal_accumulation.glsl).
bool history_still(ivec2 pixel, int layer, sampler2DArray motion_texture) {
  vec2 motion = texelFetch(motion_texture, ivec3(pixel, layer), 0).xy;
  return all(lessThanEqual(abs(motion), vec2(1.0 / 64.0)));
}
