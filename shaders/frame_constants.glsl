// The per-frame uniform block, laid out by shared_constants.h.
#include "shared_constants.h"

layout(std140, binding = DEEPGI_UBO_FRAME) uniform FrameBlock {
  FrameConstants frame;
};
