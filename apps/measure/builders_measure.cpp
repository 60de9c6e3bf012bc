// `bvhlab tradeoff --builders`: the configurations, one scene's rays and one configuration's figures.
#include "apps/measure/builders.h"
#include "apps/runtime/ray_sets.h"
#include "apps/runtime/run_record.h"
#include "apps/runtime/scene_loading.h"
#include "apps/runtime/timing.h"
#include "framework/report/build_stats_json.h"
#include "framework/report/provenance.h"
#include "framework/report/query_counters_json.h"

#include <fmt/core.h>

#include <algorithm>
#include <stdexcept>

namespace bvhlab {

using nlohmann::json;

std::vector<AccelConfig> builderConfigs(const std::string& accels) {
    std::vector<AccelConfig> configs = parseAccelConfigList(accels.empty() ? ourAccelerators() : accels);
    // The insertion pass after the builders it changes most (tdbvh) and the defaults' trees.
    for (const char* name : {"sahbvh", "sahbvh8", "ploc8", "tdbvh"}) {
        if (std::none_of(configs.begin(), configs.end(), [&](const AccelConfig& c) { return c.label == name; }))
            continue;
        AccelConfig c = parseAccelConfig(fmt::format("{}:BVH::optimize=insertion", name));
        c.label = fmt::format("{}+insertion", name);
        configs.push_back(c);
    }
    for (const char* quality : {"low", "medium", "high"}) {
        AccelConfig c = parseAccelConfig(fmt::format("embree:Embree::quality={}", quality));
        c.label = fmt::format("embree-{}", quality);
        configs.push_back(c);
    }
    return configs;
}

BuildersScene prepareBuildersScene(const std::string& id, const Env& sceneEnv, const TradeoffSettings& settings) {
    BuildersScene b;
    b.id = id;
    b.env = tradeoffSceneEnv(sceneEnv, settings, settings.raySize, settings.raySize);
    b.scene = loadSceneFor(b.env);
    b.rays = sceneRaySets(b.scene, b.env, *referenceEmbree(b.scene, b.env));
    return b;
}

json measureBuilderConfig(const BuildersScene& b, const AccelConfig& config, const TradeoffSettings& settings) {
    const Env env = accelConfigEnv(config, b.env);

    const TimedBuilds built = timedBuilds(b.scene, config, env, settings);
    const Accelerator* accel = built.accel.get();
    const BuildStats& stats = built.stats;
    const std::vector<double>& buildMs = built.buildMs;
    const std::vector<double>& buildCpuMs = built.buildCpuMs;

    const std::vector<Ray>* sets[] = {&b.rays.primary, &b.rays.shadow, &b.rays.incoherent};
    const bool counted = accel->hasCounters();
    json result = {{"scene", b.id},
                   {"config", config.label},
                   {"accel", config.name},
                   {"overrides", config.overrides},
                   {"threads", settings.threads},
                   {"prims", b.scene.triangleCount()},
                   {"build_ms", median(buildMs)},
                   {"build_ms_all", buildMs},
                   {"build_cpu_ms", median(buildCpuMs)},
                   {"build_cpu_ms_all", buildCpuMs},
                   {"provenance", provenanceJson()},
                   {"run", runJson()}};
    result.update(buildStatsJson(stats, {.mean = "avg_leaf", .largest = "max_leaf"}));
    // Through the batch calls, as the builders' figures have always been measured.
    for (size_t s = 0; s < std::size(kBuilderRaySets); ++s) {
        const RaySetQuery& asked = kRaySetQueries[s];
        const PassResult r = tracePasses(*accel, *sets[s], asked.anyHit, asked.coherence, settings.threads,
                                         settings.passes, QueryKind::Batch);
        const double q = std::max<double>(1.0, double(r.counters.queries));
        result[kBuilderRaySets[s]] = {
            {"rays", sets[s]->size()}, {"t_r_us", r.usPerQuery}, {"t_r_cpu_us", r.cpuUsPerQuery}};
        result[kBuilderRaySets[s]].update(queryCountersJson(r.counters, q, counted));
    }
    // The bare loop, Embree as its users call it (the bench's embree-bare), on the baseline's tree.
    const auto* native = dynamic_cast<const NativeBatchApis*>(accel);
    if (config.label == kBuildersBaseline && native) {
        json bare = json::object();
        for (size_t s = 0; s < std::size(kBuilderRaySets); ++s) {
            try {
                const std::unique_ptr<NativeRayBatch> batch = native->prepareNativeBatch(*sets[s]);
                const PassResult r =
                    traceNativePasses(*batch, kRaySetQueries[s].anyHit, settings.threads, settings.passes);
                bare[kBuilderRaySets[s]] = {{"t_r_us", r.usPerQuery}, {"t_r_cpu_us", r.cpuUsPerQuery}};
            } catch (const std::invalid_argument& e) {
                fmt::print(stderr, "  {}: no bare loop over the {} rays ({})\n", b.id, kBuilderRaySets[s], e.what());
                bare[kBuilderRaySets[s]] = nullptr;
            }
        }
        result["bare"] = bare;
    }
    return result;
}

}  // namespace bvhlab
