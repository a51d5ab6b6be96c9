// Constants of the radiosity visibility test (radiosity_visibility.glsl),
// shared with the CPU mirror the tests check it against, so the two cannot
// disagree. Only #define lines, so both GLSL and C++ can include it.
#ifndef DEEPGI_RADIOSITY_VISIBILITY_CONSTANTS_H
#define DEEPGI_RADIOSITY_VISIBILITY_CONSTANTS_H

// Halvings of the stretch over which the marched segment left the camera's
// sight, before the test asks whether it left through a surface
// (docs/radiosity-studies.md, "Light the allowance hid").
#define DEEPGI_RADIOSITY_CROSSING_HALVINGS 2

#endif
