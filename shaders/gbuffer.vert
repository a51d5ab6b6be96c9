#version 450 core
#include "frame_constants.glsl"

layout(location = DEEPGI_ATTRIBUTE_POSITION) in vec3 position;
layout(location = DEEPGI_ATTRIBUTE_NORMAL) in vec3 normal;
layout(location = DEEPGI_ATTRIBUTE_UV) in vec2 uv;
layout(location = DEEPGI_ATTRIBUTE_COLOUR) in vec4 colour;

out GBufferVertex {
  vec3 camera_normal;
  vec2 uv;
  vec4 colour;
  float camera_depth;           // linear, this frame
  float previous_camera_depth;  // linear, previous frame's camera (reproject)
  vec4 current_clip;
  vec4 previous_clip;
#if defined(PREDICTION_LAYER)
  vec4 next_clip;  // the next frame's camera (delay, predict): the third layer's position
#endif
} vertex_out;

void main() {
  vec4 world = vec4(position, 1.0);
  vec4 camera_position = frame.view * world;
  // The view matrix is rigid, so it transforms normals without an inverse transpose.
  vertex_out.camera_normal = mat3(frame.view) * normal;
  vertex_out.uv = uv;
  vertex_out.colour = colour;
  vertex_out.camera_depth = -camera_position.z;
  vertex_out.previous_camera_depth = -(frame.previous_view * world).z;
  vertex_out.current_clip = frame.projection * camera_position;
  vertex_out.previous_clip = frame.previous_view_projection * world;
#if defined(PREDICTION_LAYER)
  vertex_out.next_clip = frame.next_view_projection * world;
#endif
  gl_Position = vertex_out.current_clip;
}
