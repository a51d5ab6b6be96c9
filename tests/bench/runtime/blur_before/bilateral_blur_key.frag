#version 450 core
// Stands in for the key pass in blur_bench's "before" column: the blur of
// that time read the depth pyramid and G-buffer normal itself, so the key
// draw writes nothing (an empty fullscreen draw, a few ms on llvmpipe).
void main() {}
