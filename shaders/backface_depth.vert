#version 450 core
// The back-face depth pass (backface_depth.frag): positions alone.
#include "frame_constants.glsl"

layout(location = DEEPGI_ATTRIBUTE_POSITION) in vec3 position;

void main() { gl_Position = frame.projection * (frame.view * vec4(position, 1.0)); }
