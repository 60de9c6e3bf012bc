#include "accel/registry.h"

#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/bvh_env.h"
#include "accel/embree/embree_accelerator.h"
#include "accel/embree/embree_env.h"
#include "accel/naive/naive_accelerator.h"
#include "framework/core/error.h"

#include <fmt/ranges.h>

namespace bvhlab {

const std::vector<AcceleratorInfo>& acceleratorInfos() {
    static const std::vector<AcceleratorInfo> infos = {
        {"naive", "brute force: tests every triangle; the reference the others are tested against", {},
         [](const Env&) { return std::make_unique<NaiveAccelerator>(); }},
        {"embree", "Intel Embree 3 (rtcIntersect1/rtcOccluded1): the speed reference; no counters, no visible tree",
         {std::string(keys::Embree::quality.name()), std::string(keys::Embree::robust.name()),
          std::string(keys::Embree::threads.name())},
         [](const Env& env) { return std::make_unique<EmbreeAccelerator>(env); }},
        {"tdbvh", "BVH by spatial median: the middle of the longest axis (BVH::tdbvhSplit), object median fallback",
         bvhEnvKeys(BvhKind::SpatialMedian),
         [](const Env& env) {
             return std::make_unique<BvhAccelerator<Bvh>>(BvhKind::SpatialMedian, bvhConfigFromEnv(env),
                                                          traversalConfigFromEnv(env));
         }},
        {"sahbvh", "BVH by binned SAH (Wald 2007): BVH::bins bins along the widest centre axis, SSE binning",
         bvhEnvKeys(BvhKind::BinnedSah),
         [](const Env& env) {
             return std::make_unique<BvhAccelerator<Bvh>>(BvhKind::BinnedSah, bvhConfigFromEnv(env),
                                                          traversalConfigFromEnv(env));
         }},
        {"sahbvh4",
         "sahbvh's tree collapsed into 4-wide nodes, four child boxes tested at once (SSE); N_TR counts wide steps",
         bvhEnvKeys(BvhKind::BinnedSah),
         [](const Env& env) {
             return std::make_unique<BvhAccelerator<WideBvh<4>>>(BvhKind::BinnedSah, bvhConfigFromEnv(env),
                                                                 traversalConfigFromEnv(env));
         }},
        {"sweepbvh", "BVH by full-sweep SAH over all N-1 planes per axis: the exact reference for sahbvh; slow build",
         bvhEnvKeys(BvhKind::SweepSah),
         [](const Env& env) {
             return std::make_unique<BvhAccelerator<Bvh>>(BvhKind::SweepSah, bvhConfigFromEnv(env),
                                                          traversalConfigFromEnv(env));
         }},
    };
    return infos;
}

void registerAcceleratorKeys(EnvRegistry& registry) {
    std::vector<std::string> names;
    for (const AcceleratorInfo& info : acceleratorInfos()) names.push_back(info.name);
    registry.add(keys::ASDS::type.declaration(names));
    registerEmbreeKeys(registry);
    registerBvhKeys(registry);
}

std::unique_ptr<Accelerator> createAccelerator(const std::string& name, const Env& env) {
    std::vector<std::string> names;
    for (const AcceleratorInfo& info : acceleratorInfos()) {
        if (info.name == name) return info.create(env);
        names.push_back(info.name);
    }
    throw InputError(fmt::format("unknown accelerator '{}' (known: {})", name, fmt::join(names, ", ")));
}

}  // namespace bvhlab
