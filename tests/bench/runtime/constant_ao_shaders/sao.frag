#version 450 core
// A test stand-in for shaders/sao.frag (ctest bench_temporal_convergence_shaders):
// the same visibility at every pixel in every frame, so a still camera's AO
// equals the converged image's exactly when temporal_convergence --shaders
// gives this folder to both of its renderers.
layout(location = 0) out float out_visibility;

void main() { out_visibility = 0.5; }
