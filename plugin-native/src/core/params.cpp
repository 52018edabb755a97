#include "core/params.h"

#include <cmath>

namespace drape {
namespace {

bool finite3(const float v[3]) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }
float norm3(const float v[3]) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

}  // namespace

drape_params default_params() {
    drape_params p{};
    p.struct_size = sizeof(drape_params);
    p.model = DRAPE_MODEL_XPBD;
    p.stiffness[DRAPE_GROUP_STRUCTURAL] = 2000.0f;
    p.stiffness[DRAPE_GROUP_SHEAR] = 1000.0f;
    p.stiffness[DRAPE_GROUP_BEND] = 200.0f;
    p.damping = 0.05f;
    p.gravity[1] = -9.81f;
    p.air_drag = 0.1f;
    p.substeps = 0;
    p.iterations = 1;
    p.max_stretch = 0.1f;
    return p;
}

std::string validate_params(const drape_params& p, drape_status* status) {
    *status = DRAPE_ERROR_INVALID_ENUM;
    if (p.model > DRAPE_MODEL_XPBD) return "model " + std::to_string(p.model) + " is not a drape_model";
    *status = DRAPE_ERROR_NOT_FINITE;
    for (float k : p.stiffness)
        if (!std::isfinite(k)) return "stiffness is NaN or infinite";
    if (!std::isfinite(p.damping) || !std::isfinite(p.air_drag) || !finite3(p.gravity) || !finite3(p.wind) ||
        !std::isfinite(p.max_stretch))
        return "damping, air_drag, gravity, wind and max_stretch must be finite";
    *status = DRAPE_ERROR_INVALID_ARGUMENT;
    for (float k : p.stiffness) {
        if (k < 0) return "stiffness must be >= 0";
        if (p.model == DRAPE_MODEL_PBD && k > 1) return "PBD stiffness is a fraction in [0, 1]";
        if (k > 1e9f) return "stiffness above 1e9 N/m";
    }
    if (p.damping < 0 || p.damping > 1e6f) return "damping must be in [0, 1e6] N*s/m";
    if (p.air_drag < 0 || p.air_drag > 1e3f) return "air_drag must be in [0, 1000] 1/s";
    if (norm3(p.gravity) > 1e4f) return "gravity above 1e4 m/s^2";
    if (norm3(p.wind) > 1e4f) return "wind above 1e4 m/s";
    if (p.max_stretch < 0 || p.max_stretch > 100) return "max_stretch must be in [0, 100] (0 = no tethers)";
    if (p.substeps > kMaxSubsteps) return "substeps above " + std::to_string(kMaxSubsteps);
    if (p.iterations < 1 || p.iterations > kMaxIterations)
        return "iterations must be in [1, " + std::to_string(kMaxIterations) + "]";
    *status = DRAPE_OK;
    return {};
}

}  // namespace drape
