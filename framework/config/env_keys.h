// The framework's own env keys (camera, lights, rendering, output, scene).
#pragma once

#include "framework/config/env.h"

namespace bvhlab {

// `acceleratorNames` are the choices of ASDS::type.
void registerFrameworkKeys(EnvRegistry& registry, const std::vector<std::string>& acceleratorNames);

}  // namespace bvhlab
