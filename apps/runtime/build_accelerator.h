// Building the accelerator an env chooses, timed, with a report on stderr (and lines while a
// build runs longer than 2 s: build_watch.h).
#pragma once

#include "framework/config/env.h"
#include "framework/core/accelerator.h"
#include "framework/scene/scene.h"

#include <memory>

namespace bvhlab {

struct BuiltAccelerator {
    std::unique_ptr<Accelerator> accel;
    BuildStats stats;
};
BuiltAccelerator buildAccelerator(const Scene& scene, const Env& env);

}  // namespace bvhlab
