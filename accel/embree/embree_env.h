// The env keys of the `embree` accelerator (Embree::quality, Embree::robust, Embree::threads).
#pragma once

#include "framework/config/env.h"

namespace bvhlab {

void registerEmbreeKeys(EnvRegistry& registry);

}  // namespace bvhlab
