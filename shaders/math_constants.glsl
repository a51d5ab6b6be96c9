// The constants every shader shares, each as one float literal so that no
// two passes round them differently.
#ifndef DEEPGI_MATH_CONSTANTS_GLSL
#define DEEPGI_MATH_CONSTANTS_GLSL
const float pi = 3.14159265;
const float two_pi = 6.2831853;
const float inv_pi = 0.31830989;
#endif
