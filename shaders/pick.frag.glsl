#version 300 es
// Fragment stage of the grab pick (grab.vert.glsl DRAPE_PASS_PICK): writes the candidate's record
// into the slot's texel of the RGBA32UI pick target; the depth test keeps the nearest.
precision highp float;
precision highp int;
flat in highp uvec4 v_pick;
layout(location = 0) out highp uvec4 o_pick;
void main() { o_pick = v_pick; }
