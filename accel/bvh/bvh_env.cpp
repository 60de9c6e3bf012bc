#include "accel/bvh/bvh_env.h"

#include <span>

namespace bvhlab {

namespace {

// Where each Config's keys land in the settings.
BuildConfig& shared(BvhSettings& s) { return s.build.shared; }
BvhBuildConfig& build(BvhSettings& s) { return s.build; }
InsertionConfig& insertion(BvhSettings& s) { return s.build.insertion; }
TraversalConfig& traversal(BvhSettings& s) { return s.traversal; }
BvhStatsConfig& stats(BvhSettings& s) { return s.stats; }
BvhUpdateConfig& update(BvhSettings& s) { return s.update; }
BvhSettings& settings(BvhSettings& s) { return s; }

}  // namespace

const BvhKeys& bvhCommonKeys() {
    static const BvhKeys bound = BvhKeys::join({
        {kBuildKeys, shared},
        {kTraversalTestKeys, traversal},
        {kBvhThreadsKeys, settings},
        {kBvhStatsKeys, stats},
        {kBvhOptimizeKeys, build},
        {kInsertionKeys, insertion},
        {kTraversalPathKeys, traversal},
        {kBvhUpdateKeys, update},
    });
    return bound;
}

const BvhKeys& sahTerminationKeys() {
    static const BvhKeys bound(kSahTerminationKeys, shared);
    return bound;
}

const BvhKeys& spatialMedianKeys() {
    static const BvhKeys bound(
        kSpatialMedianKeys, [](BvhSettings & s) -> auto& { return s.build.spatialMedian; });
    return bound;
}

const BvhKeys& binnedSahKeys() {
    static const BvhKeys bound(
        kBinnedSahKeys, [](BvhSettings & s) -> auto& { return s.build.binnedSah; });
    return bound;
}

const BvhKeys& sbvhKeys() {
    static const BvhKeys bound(
        kSbvhKeys, [](BvhSettings & s) -> auto& { return s.build.sbvh; });
    return bound;
}

const BvhKeys& plocKeys() {
    static const BvhKeys bound(
        kPlocKeys, [](BvhSettings & s) -> auto& { return s.build.ploc; });
    return bound;
}

namespace {

std::span<const BvhKeys* const> allKeys() {
    static const BvhKeys* const all[] = {&bvhCommonKeys(), &sahTerminationKeys(), &spatialMedianKeys(),
                                         &binnedSahKeys(), &sbvhKeys(),           &plocKeys()};
    return all;
}

}  // namespace

void registerBvhKeys(EnvRegistry& registry) {
    for (const BvhKeys* keys : allKeys()) keys->registerWith(registry);
}

BvhSettings bvhSettingsFromEnv(const Env& env) {
    BvhSettings settings;
    for (const BvhKeys* keys : allKeys()) keys->read(env, settings);
    settings.build.shared.threads = settings.threads != 0 ? settings.threads : env.get(keys::SetRayTracing::threads);
    return settings;
}

}  // namespace bvhlab
