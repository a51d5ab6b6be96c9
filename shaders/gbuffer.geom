#version 450 core
// Previous and reproject: one invocation per layer sends each triangle to both
// array layers; the fragment shader applies the minimum separation on layer 1.
// (Delay and predict choose their layers in gbuffer.vert instead.)
layout(triangles, invocations = 2) in;
layout(triangle_strip, max_vertices = 3) out;

in GBufferVertex {
  vec3 camera_normal;
  vec2 uv;
  vec4 colour;
  float camera_depth;
  float previous_camera_depth;
  vec4 current_clip;
  vec4 previous_clip;
} vertex_in[];

out GBufferVertex {
  vec3 camera_normal;
  vec2 uv;
  vec4 colour;
  float camera_depth;
  float previous_camera_depth;
  vec4 current_clip;
  vec4 previous_clip;
} vertex_out;

void main() {
  for (int i = 0; i < 3; ++i) {
    vertex_out.camera_normal = vertex_in[i].camera_normal;
    vertex_out.uv = vertex_in[i].uv;
    vertex_out.colour = vertex_in[i].colour;
    vertex_out.camera_depth = vertex_in[i].camera_depth;
    vertex_out.previous_camera_depth = vertex_in[i].previous_camera_depth;
    vertex_out.current_clip = vertex_in[i].current_clip;
    vertex_out.previous_clip = vertex_in[i].previous_clip;
    gl_Position = gl_in[i].gl_Position;
    gl_Layer = gl_InvocationID;
    EmitVertex();
  }
  EndPrimitive();
}
