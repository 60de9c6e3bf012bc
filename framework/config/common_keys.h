// The env keys more than one layer reads: the thread count (the renderer's, and Embree's
// builds when Embree::threads is 0). Every program registers them.
#pragma once

#include "framework/config/env.h"

namespace bvhlab {

namespace keys::SetRayTracing {
inline constexpr IntKey threads{"SetRayTracing::threads", "0", 0, 1024,
                                "render threads (and Embree's); 0 = all hardware threads, 1 = the report's setting"};
}

void registerCommonKeys(EnvRegistry& registry);

}  // namespace bvhlab
