// Per-stage wall time of a step (drape_stage): a ProfileScope adds the time from its construction
// to its destruction to one stage's figure. Without figures to add to (profiling off) it reads no
// clock and does nothing else; it never allocates.
#pragma once

#include <chrono>

#include "drape/drape.h"

namespace drape {

class ProfileScope {
public:
    /// stage_ms: DRAPE_STAGE_COUNT figures in ms (drape_stats.stage_ms), or nullptr: off.
    ProfileScope(float* stage_ms, drape_stage stage) : stage_ms_(stage_ms), stage_(stage) {
        if (stage_ms_) start_ = std::chrono::steady_clock::now();
    }
    ~ProfileScope() {
        if (stage_ms_)
            stage_ms_[stage_] +=
                std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - start_).count();
    }
    ProfileScope(const ProfileScope&) = delete;
    ProfileScope& operator=(const ProfileScope&) = delete;

private:
    float* const stage_ms_;
    const drape_stage stage_;
    std::chrono::steady_clock::time_point start_{};
};

}  // namespace drape
