// The env keys of the BVH accelerators (builder_table.h), all in section BVH::. Each is declared
// once, beside the Config field it fills (a FieldKey: builders/*.h, traversal_config.h,
// bvh_accelerator.h), in its Config's list of keys; bvh_env.cpp binds each list, once, to the
// part of BvhSettings it fills: the bindings declare the keys to the registrar and read them.
#pragma once

#include "accel/bvh/builders/bvh_builder.h"
#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/traverse/traversal_config.h"
#include "framework/config/common_keys.h"
#include "framework/config/env.h"
#include "framework/config/key_bindings.h"

#include <span>
#include <tuple>
#include <vector>

namespace bvhlab {

// Everything a BVH accelerator is configured with.
struct BvhSettings {
    BvhBuildConfig build;
    TraversalConfig traversal;
    BvhStatsConfig stats;
    BvhUpdateConfig update;
    int threads = 0;  // BVH::threads as given; 0 = SetRayTracing::threads. build.shared.threads is the count
};

namespace keys::BVH {
inline constexpr FieldKey<&BvhSettings::threads> threads{
    "BVH::threads", 0, 1024,
    "build threads; 0 = as SetRayTracing::threads (0 there: all hardware threads). The tree is the same whatever the "
    "count"};
}  // namespace keys::BVH
inline constexpr std::tuple kBvhThreadsKeys{&keys::BVH::threads};

using BvhKeys = KeyBindings<BvhSettings>;

// The keys of the builders' own options; builder_table.cpp says which builder reads which.
const BvhKeys& sahTerminationKeys();
const BvhKeys& spatialMedianKeys();
const BvhKeys& binnedSahKeys();
const BvhKeys& sbvhKeys();
const BvhKeys& plocKeys();

// The declarations of the keys of `own`, then of those every BVH accelerator reads.
std::vector<EnvKey> bvhKeyDeclarations(std::span<const BvhKeys* const> own);

// The values of the keys of `own` and of those every BVH accelerator reads, as a structure reads its keys
// (<bvhlab/settings.h>); BVH::threads 0 is SetRayTracing::threads.
BvhSettings bvhSettings(const PluginSettings& keys, std::span<const BvhKeys* const> own);
// Every BVH key's value in `env`.
BvhSettings bvhSettingsFromEnv(const Env& env);

}  // namespace bvhlab
