// Records and constants that the C++ backends and the GLSL passes share, written once in the common
// subset of C++ and GLSL (#define only). C++ includes this file; embed_shaders.cmake splices it into a
// shader in place of its `#include "layout.h"` line (GLSL ES has no #include).
#ifndef DRAPE_SHADERS_LAYOUT_H
#define DRAPE_SHADERS_LAYOUT_H

#ifdef GL_ES  // C++ has these from drape.h
// GENERATED BEGIN ShaderEnums (tools/abi/generate.py from tools/abi/abi.py: do not edit)
#define DRAPE_GROUP_STRUCTURAL 0
#define DRAPE_GROUP_SHEAR 1
#define DRAPE_GROUP_BEND 2
#define DRAPE_GROUP_COUNT 3
#define DRAPE_COLLIDER_SPHERE 0
#define DRAPE_COLLIDER_CAPSULE 1
#define DRAPE_COLLIDER_BOX 2
#define DRAPE_COLLIDER_PLANE 3
// GENERATED END ShaderEnums
#endif

// Texels per row of every GLES texture (kTexWidth; ES 3.0 guarantees GL_MAX_TEXTURE_SIZE >= 2048,
// rows are checked against the real limit). A constant, not a uniform: texel() divides by it once
// per fetch, and a division by a uniform cost llvmpipe, which has no vector integer division, 38 %
// of an IMPLICIT Jacobi pass (33^2 curtain: 0.387 -> 0.241 ms a pass, thread CPU).
#define DRAPE_TEX_WIDTH 1024

// Collider record of one substep (kernels::CollideShape), DRAPE_COLLIDER_VEC4 vec4s per collider:
// (pos0, margin), (pos1, friction), rot0 (x, y, z, w), rot1, (size, shape).
#define DRAPE_COLLIDER_VEC4 5

// Touch drag records (GlesCloth::drag, sim.vert.glsl drag_share): per drape_cloth_drag call a view of
// DRAPE_DRAG_VIEW_VEC4 vec4s: projection * view * world (with the cloth's origin) in columns 0-3, its
// inverse in 4-7, (viewport px, share of the offset applied in this substep, 0); per touch
// DRAPE_TOUCH_VEC4 vec4s: (position px, motion px), (amplitude, sigma px^2, its call's view, 0).
#define DRAPE_DRAG_VIEW_VEC4 9
#define DRAPE_TOUCH_VEC4 2

// XPBD on GLES: the most vec4s of lambdas (4 neighbour slots each) a displacement-iterate record
// carries; sim.vert.glsl declares that many attributes and varyings (32 slots).
#define DRAPE_MAX_LAMBDA_VEC4 8

// IMPLICIT's coarse levels on GLES (backend/gles/gles_coarse.h): members per aggregate (texels of 4
// indices), the index that means none, and the weight of the Jacobi smoothing on the coarse levels
// (2/3: damps a Laplacian's upper half of the spectrum by at least 1/3).
#define DRAPE_MAX_MEMBERS 8
#define DRAPE_NO_NODE 0xFFFFFFFFu
#define DRAPE_COARSE_WEIGHT 0.6666667

// Iterations of the swept (sphere-traced) entry search of the collision pass. Each advances by the
// exact distance, so few are needed except for grazing motion, where a slightly late entry point
// does no harm.
#define DRAPE_SWEEP_ITERATIONS 16

#endif
