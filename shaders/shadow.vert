#version 450 core
#include "shared_constants.h"
// Depth only: the shadow program has no fragment shader.
layout(location = DEEPGI_ATTRIBUTE_POSITION) in vec3 position;
layout(location = DEEPGI_UNIFORM_LIGHT_VIEW_PROJECTION) uniform mat4 light_view_projection;

void main() {
  gl_Position = light_view_projection * vec4(position, 1.0);
}
