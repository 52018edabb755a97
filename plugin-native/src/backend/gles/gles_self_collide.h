// Self-collision on the GLES backend: the CPU's self-collide stage (backend/cpu/cpu_collide.cpp,
// kernels in backend/cpu/self_collide.h; the contact maths is shaders/self_contact.h, shared) in
// OpenGL ES 3.0 passes, run after each substep's solve and tethers, before drag and colliders, and
// only when self-collision is on: a cloth without it makes no extra GL call.
//
// Per substep (no readback, no upload):
//   hash: kSelfLayers draws of the particles as points into R32UI textures of the cell hash's
//     buckets (self_hash.vert.glsl / self_hash.frag.glsl), each keeping one particle per bucket,
//     the largest index below the previous layer's, so a bucket holds up to kSelfLayers particles;
//   collide: one transform-feedback pass (self_collide.vert.glsl): each particle reads the buckets
//     of the 27 cells around its own and corrects itself by the mean of its pair corrections, as
//     the CPU's Jacobi gather, into x and d (the velocity follows).
// Unlike the CPU there is no candidate list: the hash is rebuilt every substep at the substep's
// end positions with cells of kSelfCellGles thicknesses, so a pair that passed through each other
// is caught while the pair's relative motion in one substep stays below (kSelfCellGles - 1)
// thicknesses. A bucket with more than kSelfLayers particles (a dense crumple, or cells sharing a
// bucket) keeps the kSelfLayers largest indices: a dropped particle is not found by the others, but
// it still finds those kept and pushes itself away, at its share of the correction.
#pragma once

#include <cstdint>

#include "backend/gles/gl_loader.h"
#include "core/cloth.h"  // Result

namespace drape::gles {

class GlesCloth;

/// Particles per hash bucket (hash layers: one draw each per substep). The collide pass samples
/// them all: 5 + kSelfLayers vertex texture units (ES 3.0 guarantees 16).
constexpr uint32_t kSelfLayers = 8;
/// Cell size of the GLES hash in thicknesses (>= 1: every particle closer than a thickness lies in
/// the 27 cells around a particle's own). 1.5: a pair is caught passing through each other while it
/// moves less than half a thickness relative to each other per substep.
constexpr float kSelfCellGles = 1.5f;
/// Texture units of the self-collide passes, above the simulation's (gles_cloth.cpp kSetupUnit = 7):
/// rest positions, then the hash layers.
constexpr int kSelfRestUnit = 8, kSelfLayerUnit0 = 9;

/// A cloth's self-collision GL objects, part of its GlObjects (deleted or forgotten with them).
struct SelfCollideGl {
    GLuint layers[kSelfLayers] = {};  ///< R32UI, kTexWidth x rows: particle + 1 per bucket, 0 = empty
    GLuint fbos[kSelfLayers] = {};    ///< layer k as colour attachment 0
    GLuint rest = 0;                  ///< RGBA32UI: rest positions (float bits), texel i
    GLuint first = 0, peel = 0, collide = 0;  ///< programs: layer 0, layers 1.., the collide pass
    uint32_t rows = 0;                ///< of the layer textures; buckets = kTexWidth * rows
    GLint u_prev = -1, u_collide_x = -1, u_collide_aux = -1;
    int unit_x = -1, unit_aux = -1;   ///< units u_x / u_aux of the collide program are set to
    float thickness = 0, friction = 0;  ///< the setting the programs' uniforms hold (0: none yet)
};
/// Deletes them (their context current).
void delete_self_collide_gl(SelfCollideGl& o);

/// The passes, run by GlesCloth::gpu_step (a friend of GlesCloth).
class GlesSelfCollide {
public:
    /// Before the step's passes: GL objects and programs made on first use, the device's limits
    /// checked (DRAPE_ERROR_BACKEND_UNAVAILABLE naming the one below what this needs), uniforms
    /// updated when the setting changed.
    static Result prepare(GlesCloth& c);
    /// For the duration of the passes of one step: the layer and rest textures bound on their
    /// units, what the hash draws need (viewport, colour mask, no scissor); the caller's
    /// bindings of those units and its colour mask restored at the end.
    class StepScope {
    public:
        explicit StepScope(GlesCloth& c);
        ~StepScope();
        StepScope(const StepScope&) = delete;
        StepScope& operator=(const StepScope&) = delete;

    private:
        GlesCloth& c_;
        GLint saved_[kSelfLayers + 1] = {};
        GLboolean mask_[4] = {};
    };
    /// One substep: hash of the positions in buffer x, then x and d (buffers) corrected into out_x
    /// and out_d.
    static void run(GlesCloth& c, int x, int d, int out_x, int out_d);
};

}  // namespace drape::gles
