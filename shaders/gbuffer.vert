#version 450 core
// Variants (defines from gbuffer_pass.cpp):
//   none              peel: one layer per draw
//   SINGLE_PASS       previous / reproject: drawn with 2 instances, instance i
//                     into array layer i
//   PREDICTION_LAYER  delay / predict (with SINGLE_PASS): drawn with 3
//                     instances, layer 2 placed by the next frame's camera
#if defined(SINGLE_PASS)
// The layer is chosen here, not in a geometry shader, so that every layer's
// positions go through the same vertex stage as peel's: on llvmpipe a
// geometry shader moves the viewport transform to another code path, which
// rounds window x and y differently and so the interpolated depth (docs/deepgi.md,
// "Generators").
#extension GL_ARB_shader_viewport_layer_array : require
#endif
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
  gl_Position = vertex_out.current_clip;
#if defined(SINGLE_PASS)
  gl_Layer = gl_InstanceID;
#endif
#if defined(PREDICTION_LAYER)
  // The third layer: the next frame's camera, the depth the next frame peels against.
  // The same expression as current_clip's, with the next frame's matrices.
  if (gl_InstanceID == 2) gl_Position = frame.next_projection * (frame.next_view * world);
#endif
}
