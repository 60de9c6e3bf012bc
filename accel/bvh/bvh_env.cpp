#include "accel/bvh/bvh_env.h"

#include "framework/config/plugin_settings.h"

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

// The keys every BVH accelerator reads, whatever its builder.
const BvhKeys& commonKeys() {
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

}  // namespace

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

std::vector<EnvKey> bvhKeyDeclarations(std::span<const BvhKeys* const> own) {
    std::vector<EnvKey> keys;
    for (const BvhKeys* part : own) part->appendDeclarations(keys);
    commonKeys().appendDeclarations(keys);
    return keys;
}

BvhSettings bvhSettings(const PluginSettings& keys, std::span<const BvhKeys* const> own) {
    BvhSettings settings;
    for (const BvhKeys* part : own) part->read(keys, settings);
    commonKeys().read(keys, settings);
    settings.build.shared.threads = settings.threads != 0 ? settings.threads : keys.getInt(kThreadsKey);
    return settings;
}

BvhSettings bvhSettingsFromEnv(const Env& env) {
    static const BvhKeys* const all[] = {&sahTerminationKeys(), &spatialMedianKeys(), &binnedSahKeys(), &sbvhKeys(),
                                         &plocKeys()};
    std::vector<std::string> names;
    for (const EnvKey& key : bvhKeyDeclarations(all)) names.push_back(key.name);
    return bvhSettings(EnvPluginSettings(env, std::move(names), "the BVH keys"), all);
}

}  // namespace bvhlab
