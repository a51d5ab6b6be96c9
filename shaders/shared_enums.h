// The layer count, the temporal filters' cap, the march's ray and step
// counts and the values of the renderer's enums, shared by GLSL and C++: the C++ enums in
// runtime/include/deepgi/settings.hpp take their values from these, so the
// two sides cannot disagree. Only #define lines, so it can be included
// anywhere (also from the public settings header).
#ifndef DEEPGI_SHARED_ENUMS_H
#define DEEPGI_SHARED_ENUMS_H

#define DEEPGI_LAYER_COUNT 2  // deep G-buffer layers

// The temporal filters' history under a still camera is the running mean of
// at most this many frames (temporal_accumulation.glsl; the choice is argued
// in docs/radiosity.md, "Temporal accumulation"). Public, as the layer count is.
#define DEEPGI_TEMPORAL_CAP 256

#define DEEPGI_GENERATOR_PEEL 0
#define DEEPGI_GENERATOR_PREVIOUS 1
#define DEEPGI_GENERATOR_REPROJECT 2
#define DEEPGI_GENERATOR_DELAY 3    // knows the next frame's camera (one frame of latency)
#define DEEPGI_GENERATOR_PREDICT 4  // extrapolates the next frame's camera

#define DEEPGI_LIGHT_DIRECTIONAL 0
#define DEEPGI_LIGHT_SPOT 1
#define DEEPGI_LIGHT_POINT 2

#define DEEPGI_VIEW_FINAL 0
#define DEEPGI_VIEW_NORMAL_LAYER0 1
#define DEEPGI_VIEW_NORMAL_LAYER1 2
#define DEEPGI_VIEW_ALBEDO_LAYER0 3
#define DEEPGI_VIEW_ALBEDO_LAYER1 4
#define DEEPGI_VIEW_EMISSIVE 5
#define DEEPGI_VIEW_MOTION 6
#define DEEPGI_VIEW_DEPTH_LAYER0 7
#define DEEPGI_VIEW_DEPTH_LAYER1 8
#define DEEPGI_VIEW_DIRECT_LAYER0 9
#define DEEPGI_VIEW_DIRECT_LAYER1 10

#define DEEPGI_AO_METHOD_PUBLISHED 0    // 1 - sqrt(pi/N * sum AO(X, Y))
#define DEEPGI_AO_METHOD_SOLID_ANGLE 1  // the reference's integral over the seen surface
#define DEEPGI_AO_METHOD_MARCH 2        // the reference's rays, marched through slabs behind both layers
#define DEEPGI_AO_METHOD_SPIRAL_THICK 3  // the spiral taps' solids, unioned in a hemisphere bitmask
#define DEEPGI_AO_METHOD_GTAO 4         // horizons per screen-space slice (Jimenez et al. 2016)
#define DEEPGI_AO_METHOD_BITMASK 5      // 32 sectors per slice, thick samples (Therrien et al. 2023)

// The march (sao.frag): cosine-weighted rays per pixel and evenly spaced steps
// per ray. Steps matter more than rays: with 8 steps a ray jumps over the
// near field of a crease (docs/deep-sao.md, "The march").
#define DEEPGI_AO_MARCH_RAYS 4
#define DEEPGI_AO_MARCH_STEPS 16

#define DEEPGI_RADIOSITY_METHOD_PUBLISHED 0  // 2 pi / M * sum B cos_x over the M used samples
#define DEEPGI_RADIOSITY_METHOD_AREA 1       // the reference's integral over the seen surface

#define DEEPGI_VIEW_AO_RAW 11
#define DEEPGI_VIEW_AO_BLURRED 12
// Deep radiosity: E (tonemapped) raw per layer and blurred, and the confidence
// (grey: the share of the hemisphere the taps covered, or of taps used).
#define DEEPGI_VIEW_RADIOSITY_LAYER0 13
#define DEEPGI_VIEW_RADIOSITY_LAYER1 14
#define DEEPGI_VIEW_RADIOSITY_BLURRED 15
#define DEEPGI_VIEW_RADIOSITY_CONFIDENCE 16
// The temporally filtered visibility (before the blur), and the prepare pass's
// outgoing radiance B of layer 0 at its finest level (tonemapped).
#define DEEPGI_VIEW_AO_TEMPORAL 17
#define DEEPGI_VIEW_RADIOSITY_PREPARED 18
#define DEEPGI_VIEW_REFLECTION_HIT_LAYER 19  // mirror pixels: none / layer 0 / layer 1 hit

#endif
