// The env keys of the BVH accelerators (tdbvh, sahbvh, sweepbvh), all in section BVH::.
#pragma once

#include "accel/bvh/build/bvh_builder.h"
#include "framework/config/env.h"

#include <string>
#include <vector>

namespace bvhlab {

void registerBvhKeys(EnvRegistry& registry);

// The keys each builder reads (for AcceleratorInfo::envKeys).
std::vector<std::string> bvhEnvKeys(BvhKind kind);

BvhBuildConfig bvhConfigFromEnv(const Env& env);

}  // namespace bvhlab
