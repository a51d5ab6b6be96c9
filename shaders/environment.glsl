// The environment of compose.frag and the reflections: irradiance onto a
// surface with world-space normal n. Constant scenes: pi * ambient (a
// uniform sky of radiance `ambient`). Sky scenes: a dome of the background
// colour above and a dim ground below, blended by how far the normal points
// up. Needs frame_constants.glsl and math_constants.glsl.
#ifndef DEEPGI_ENVIRONMENT_GLSL
#define DEEPGI_ENVIRONMENT_GLSL
vec3 environment_irradiance(vec3 world_normal) {
  if (dot(frame.background.rgb, vec3(1.0)) <= 0.0) return pi * frame.ambient.rgb;
  float up = 0.5 + 0.5 * world_normal.y;
  vec3 sky = frame.ambient.rgb + 0.25 * frame.background.rgb;
  vec3 ground = frame.ambient.rgb * 0.5;
  return pi * mix(ground, sky, up);
}
#endif
