// Hable's filmic curve: a toe that keeps shadows from crushing and a shoulder
// that rolls highlights off instead of clipping them.
vec3 filmic_curve(vec3 x) {
  const float shoulder = 0.15, linear_strength = 0.50, linear_angle = 0.10;
  const float toe = 0.20, toe_numerator = 0.02, toe_denominator = 0.30;
  return ((x * (shoulder * x + linear_angle * linear_strength) + toe * toe_numerator) /
          (x * (shoulder * x + linear_strength) + toe * toe_denominator)) - toe_numerator / toe_denominator;
}

vec3 filmic_tonemap(vec3 radiance) {
  const float white_point = 11.2;
  const float exposure_bias = 2.0;
  return clamp(filmic_curve(radiance * exposure_bias) / filmic_curve(vec3(white_point)), 0.0, 1.0);
}
