// The env keys more than one layer reads: the thread count (the renderer's, and every
// structure's build: <bvhlab/settings.h>). Every program registers them.
#pragma once

#include "framework/config/env.h"

namespace bvhlab {

namespace keys::SetRayTracing {
inline constexpr IntKey threads{
    kThreadsKey, "0", 0, 1024,
    "render threads, and the structures' build threads where theirs say 0; 0 = all hardware threads, 1 = the "
    "report's setting"};
}

void registerCommonKeys(EnvRegistry& registry);

}  // namespace bvhlab
