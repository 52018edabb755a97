#version 300 es
// Fragment stage of the simulation programs: ES 3.0 needs one to link. Transform-feedback passes
// run with GL_RASTERIZER_DISCARD, so it never executes there; the sleep check's points reach it
// (into the cloth's own 1x1 target), where it only has to let the occlusion query count them.
precision mediump float;
out vec4 o_color;
void main() { o_color = vec4(0.0); }
