// Encodings shared by the pass that writes the G-buffer and the passes that read it.

// Octahedral map: a unit normal in two numbers of equal precision everywhere,
// which an RG16F target keeps to about 1e-3.
vec2 encode_normal(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  vec2 folded = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return n.z >= 0.0 ? n.xy : folded;
}

vec3 decode_normal(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  float t = max(-n.z, 0.0);
  n.x += n.x >= 0.0 ? -t : t;
  n.y += n.y >= 0.0 ? -t : t;
  return normalize(n);
}

// Albedo is stored sRGB-encoded in RGBA8 (dark colours keep their precision);
// encoded by hand so reading the texture back never depends on driver sRGB rules.
vec3 srgb_encode(vec3 linear) {
  vec3 c = clamp(linear, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// The albedo target's alpha: 1 for diffuse surfaces, this for mirrors (whose
// albedo is then their reflectance); readers test is_mirror_alpha.
const float gbuffer_mirror_alpha = 0.0;
bool is_mirror_alpha(float alpha) { return alpha < 0.5; }

vec3 srgb_decode(vec3 encoded) {
  return mix(encoded / 12.92, pow((encoded + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), encoded));
}

// Depth buffers hold near/z (reversed Z, infinite far): 0 means nothing was hit.
float linear_depth_from_stored(float stored, float near_plane) {
  return stored > 0.0 ? near_plane / stored : 1.0e30;
}

// Camera-space position of a pixel centre at a linear depth.
vec3 camera_position_at(vec2 pixel_centre, float linear_depth, vec4 internal_size, vec4 ray_scale) {
  vec2 ndc = pixel_centre * internal_size.zw * 2.0 - 1.0;
  return vec3(ndc * ray_scale.xy * linear_depth, -linear_depth);
}
