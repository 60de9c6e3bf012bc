#include "accel/registry.h"

#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/bvh_env.h"
#include "accel/embree/embree_accelerator.h"
#include "accel/embree/embree_env.h"
#include "accel/guarded_accelerator.h"
#include "accel/naive/naive_accelerator.h"
#include "framework/core/error.h"

#include <fmt/ranges.h>

namespace bvhlab {

namespace {

// A BVH accelerator: the builder `kind` over the node layout `Layout`.
template <typename Layout>
AcceleratorInfo bvhInfo(std::string name, std::string description, BvhKind kind) {
    return {std::move(name), std::move(description), bvhEnvKeys(kind), [kind](const Env& env) {
                return std::make_unique<BvhAccelerator<Layout>>(kind, bvhConfigFromEnv(env), traversalConfigFromEnv(env),
                                                                statsConfigFromEnv(env));
            },
            {}};
}

std::vector<AcceleratorInfo>& registeredInfos() {
    static std::vector<AcceleratorInfo> infos = {
        {"naive", "brute force: tests every triangle; the reference the others are tested against", {},
         [](const Env&) { return std::make_unique<NaiveAccelerator>(); }, {}},
        {"embree", "Intel Embree 3 (rtcIntersect1/rtcOccluded1): the speed reference; no counters, no visible tree",
         {std::string(keys::Embree::quality.name()), std::string(keys::Embree::robust.name()),
          std::string(keys::Embree::threads.name())},
         [](const Env& env) { return std::make_unique<EmbreeAccelerator>(env); }, {}},
        bvhInfo<Bvh>("tdbvh", "BVH by spatial median: the middle of the longest axis (BVH::tdbvhSplit), object median fallback",
                     BvhKind::SpatialMedian),
        bvhInfo<Bvh>("sahbvh", "BVH by binned SAH (Wald 2007): BVH::bins bins along the widest centre axis, SSE binning",
                     BvhKind::BinnedSah),
        bvhInfo<WideBvh<4>>(
            "sahbvh4", "sahbvh's tree (leaves charged by blocks of eight) in 4-wide nodes, four child boxes tested at once (SSE), "
            "leaves eight triangles at once (AVX2); N_TR counts wide steps",
            BvhKind::BinnedSah),
        bvhInfo<WideBvh<8>>("sahbvh8",
                            "sahbvh's tree (leaves charged by blocks of eight) in 8-wide nodes, eight child boxes tested at "
                            "once (AVX2; scalar lanes without it), leaves eight triangles at once; N_TR counts wide steps",
                            BvhKind::BinnedSah),
        bvhInfo<Bvh>("sbvh",
                     "split BVH (Stich et al. 2009): sahbvh's object splits and, where their children overlap "
                     "(BVH::sbvhAlpha), spatial splits that clip triangles to bins, within BVH::sbvhGrowth more references",
                     BvhKind::Sbvh),
        bvhInfo<WideBvh<8>>("sbvh8",
                            "sbvh's tree (leaves charged by blocks of eight) in 8-wide nodes, as sahbvh8; N_TR counts wide steps",
                            BvhKind::Sbvh),
        bvhInfo<Bvh>("ploc",
                     "BVH by PLOC (Meister & Bittner 2018): Morton order, mutual nearest neighbours within BVH::plocRadius "
                     "merged bottom-up in parallel, leaves formed by SAH",
                     BvhKind::Ploc),
        bvhInfo<WideBvh<8>>("ploc8",
                            "ploc's tree (leaves charged by blocks of eight) in 8-wide nodes, as sahbvh8; N_TR counts wide steps",
                            BvhKind::Ploc),
        bvhInfo<Bvh>("sweepbvh", "BVH by full-sweep SAH over all N-1 planes per axis: the exact reference for sahbvh; slow build",
                     BvhKind::SweepSah),
    };
    return infos;
}

}  // namespace

const std::vector<AcceleratorInfo>& acceleratorInfos() { return registeredInfos(); }

const AcceleratorInfo* findAccelerator(const std::string& name) {
    for (const AcceleratorInfo& info : registeredInfos())
        if (info.name == name) return &info;
    return nullptr;
}

void addAccelerator(AcceleratorInfo info) {
    if (const AcceleratorInfo* taken = findAccelerator(info.name))
        throw InputError(fmt::format("{}: accelerator '{}' is already defined by {}", info.plugin, info.name,
                                     taken->plugin.empty() ? "bvhlab" : taken->plugin));
    info.create = [create = std::move(info.create), plugin = info.plugin, name = info.name](const Env& env) {
        std::unique_ptr<Accelerator> accel = guardPlugin(plugin, name, "its factory", [&] { return create(env); });
        if (!accel) throw PluginError(fmt::format("plugin {}, accelerator '{}': its factory returned nothing", plugin, name));
        return guardAccelerator(std::move(accel), plugin, name);
    };
    registeredInfos().push_back(std::move(info));
}

void registerAcceleratorKeys(EnvRegistry& registry) {
    std::vector<std::string> names;
    for (const AcceleratorInfo& info : acceleratorInfos()) names.push_back(info.name);
    registry.add(keys::ASDS::type.declaration(names));
    registry.add(keys::ASDS::plugins);
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
