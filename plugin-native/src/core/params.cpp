#include "core/params.h"

#include <algorithm>
#include <cmath>

#include "core/abi_tables.h"
#include "core/topology.h"

namespace drape {

drape_params default_params() { return abi::Layout<drape_params>::defaults(); }

drape_params resolve_model(drape_params p) {
    if (p.model == DRAPE_MODEL_AUTO) p.model = DRAPE_MODEL_IMPLICIT;
    return p;
}

std::string validate_params(const drape_params& p, drape_status* status) {
    std::string problem;
    *status = abi::Layout<drape_params>::check(p, &problem);  // tools/abi/abi.py: enums, finite, ranges
    if (*status != DRAPE_OK) return problem;
    *status = DRAPE_ERROR_INVALID_ARGUMENT;
    if (p.model == DRAPE_MODEL_PBD)
        for (float k : p.stiffness)
            if (k > 1) return "PBD stiffness is a fraction in [0, 1]";
    *status = DRAPE_OK;
    return {};
}

float mass_spring_max_substep(float inverse_mass, float stiffness_sum, float damping, uint32_t active_springs) {
    const float w = inverse_mass;
    if (w == 0 || active_springs == 0) return INFINITY;
    const float a = 2.0f * w * stiffness_sum;
    const float b = 2.0f * w * damping * float(active_springs);
    const float s = kStabilitySafety;
    return a > 0 ? (-b + std::sqrt(b * b + 4.0f * s * s * a)) / a : 2.0f * s * s / std::max(b, 1e-30f);
}

namespace {
uint32_t clamp_substeps(float s) { return s < 1 ? 1u : s > float(kMaxSubsteps) ? kMaxSubsteps : uint32_t(s); }
}  // namespace

uint32_t gles_implicit_substeps(float dt, float h_max) { return clamp_substeps(std::ceil(dt / h_max - 1e-3f)); }

uint32_t substeps_for(const drape_params& p, drape_backend backend, float h_max,
                      const uint32_t spring_count[DRAPE_GROUP_COUNT], float dt) {
    if (p.substeps > 0) return p.substeps;
    const bool gles_implicit = p.model == DRAPE_MODEL_IMPLICIT && backend == DRAPE_BACKEND_GLES;
    if (p.model == DRAPE_MODEL_IMPLICIT && !gles_implicit) return kAutoSubstepsImplicit;
    if (p.model != DRAPE_MODEL_MASS_SPRING && !gles_implicit) return kAutoSubstepsPositionBased;
    float factor = 1;  // GLES IMPLICIT: kMaxStiffSubstepFactorGles
    if (gles_implicit && spring_count[DRAPE_GROUP_SHEAR] > 0 && p.stiffness[DRAPE_GROUP_STRUCTURAL] > 0) {
        const float shear = p.stiffness[DRAPE_GROUP_SHEAR];
        const float ratio = shear > 0 ? p.stiffness[DRAPE_GROUP_STRUCTURAL] / shear : INFINITY;
        factor = std::min(kMaxStiffSubstepFactorGles, std::max(1.0f, std::sqrt(std::sqrt(0.5f * ratio))));
    }
    if (gles_implicit) return gles_implicit_substeps(dt * factor, kMaxAutoSubstepImplicitGles);
    return clamp_substeps(std::ceil(dt / h_max));
}

StabilityEstimate estimate_stability(const Topology& topo, const drape_params& p, drape_backend backend, float dt) {
    float h_max = INFINITY;
    if (p.model == DRAPE_MODEL_MASS_SPRING) {
        const NeighbourTable& nb = topo.nbr;
        for (uint32_t i = 0; i < topo.particle_count; ++i) {
            uint32_t active = 0;
            float ksum = 0;
            for (uint32_t s = 0; s < nb.count[i]; ++s) {
                const uint8_t g = nb.group[size_t(i) * nb.slots + s];
                if (p.stiffness[g] > 0) {
                    ++active;
                    ksum += p.stiffness[g];
                }
            }
            h_max = std::min(h_max, mass_spring_max_substep(1.0f / topo.mass[i], ksum, p.damping, active));
        }
    }
    StabilityEstimate e{};
    e.substeps = substeps_for(p, backend, h_max, topo.spring_count, dt);
    const bool bounded = p.model == DRAPE_MODEL_MASS_SPRING && std::isfinite(h_max);
    const double needed = bounded ? std::ceil(double(dt) / double(h_max)) : 1.0;
    e.stable_substeps = needed >= 4294967295.0 ? UINT32_MAX : std::max(1u, uint32_t(needed));
    e.max_stable_substep = bounded ? h_max : 0.0f;
    return e;
}

}  // namespace drape
