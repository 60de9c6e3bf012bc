// The one clock around a build (and an update): every caller (render, bench, tradeoff, stress,
// check, spd) times Accelerator::build() here, so that T_B means the same for every structure, ours and a
// plugin's, and no structure times itself or has to leave its statistics out of its own time.
#pragma once

#include "framework/core/accelerator.h"

#include <functional>
#include <optional>

namespace bvhlab {

// Builds `accel` over `prims`, timing build() alone in wall time and process CPU time, then
// returns its statistics() with buildMs and buildCpuMs set. Runs on the calling thread (inside
// the caller's tbb::task_arena, which then bounds the build's threads and the statistics').
BuildStats timedBuild(Accelerator& accel, const PrimitiveSet& prims);

// Updates `accel` to `prims` (Accelerator::update), timing update() alone as timedBuild times
// build(): the updated structure's statistics with buildMs and buildCpuMs the update's (T_update).
// std::nullopt when the structure has no update (it is as it was; build it again). With
// `statisticsTimed` the statistics count in T_update: for a caller that decides by them.
std::optional<BuildStats> timedUpdate(Accelerator& accel, const PrimitiveSet& prims, bool statisticsTimed = false);

// Any other change of a structure (two levels' moveInstances), timed as timedBuild times build().
BuildStats timedChange(Accelerator& accel, const std::function<void()>& change);

}  // namespace bvhlab
