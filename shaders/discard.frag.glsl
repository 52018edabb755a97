#version 300 es
// Fragment stage of the transform-feedback programs: ES 3.0 needs one to link, but every pass
// runs with GL_RASTERIZER_DISCARD, so it never executes.
precision mediump float;
out vec4 o_color;
void main() { o_color = vec4(0.0); }
