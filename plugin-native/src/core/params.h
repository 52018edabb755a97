// Per-cloth parameters: validation, defaults, and the per-group constants a (sub)step uses.
#pragma once

#include <string>

#include "drape/drape.h"

namespace drape {

/// Defaults documented in drape.h.
drape_params default_params();

/// Empty string when valid; otherwise what is wrong (status in *status).
std::string validate_params(const drape_params& p, drape_status* status);

/// Substeps used by default for the position-based models ("small steps", Macklin et al. 2019:
/// at equal cost substeps x iterations, 16 x 1 beat 4 x 4 on every scene of tests/bench:
/// E2 0.070 vs 0.101 on the two-corner cloth, 0.039 vs 0.147 on the R4 chain).
constexpr uint32_t kAutoSubstepsPositionBased = 16;
/// Upper bound on substeps per step, automatic or given.
constexpr uint32_t kMaxSubsteps = 1000;
constexpr uint32_t kMaxIterations = 1000;
/// Fraction of the explicit stability limit used when MASS_SPRING picks substeps itself.
constexpr float kStabilitySafety = 0.9f;
/// Jacobi coupling weight theta (kernels.h jacobi_scale); convergent for theta > 1/2.
constexpr float kJacobiCoupling = 0.6f;
/// Strain beyond which a step counts as diverged ("runaway strain", accuracy.md).
constexpr float kRunawayStrain = 10.0f;

}  // namespace drape
