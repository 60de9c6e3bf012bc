#include "accel/registry.h"

#include "accel/bvh/builder_table.h"
#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/bvh_env.h"
#include "accel/embree/embree_accelerator.h"
#include "accel/naive/naive_accelerator.h"
#include "accel/plugins/guarded_accelerator.h"
#include "accel/plugins/plugin_builder.h"
#include "framework/core/error.h"

#include <fmt/ranges.h>

namespace bvhlab {

namespace {

std::string wideDescription(const std::string& builder, int width) {
    return fmt::format(
        "{}'s tree (leaves charged by blocks of eight) in {}-wide nodes, {} child boxes tested at "
        "once, leaves eight triangles at once, in the SIMD kernels BVH::isa chooses at run time; N_TR "
        "counts wide steps",
        builder, width, width == 4 ? "four" : "eight");
}

// The accelerator of a builder over one layout: NAME (binary), NAME4 or NAME8. `makeBuilder`
// gives the builder with the env's values (a plugin's reads its own keys there).
using BuilderMaker = std::function<BuilderRecord(const Env&)>;

template <typename Layout>
std::unique_ptr<Accelerator> makeBvhAccelerator(const BuilderMaker& makeBuilder, const Env& env) {
    const BvhSettings settings = bvhSettingsFromEnv(env);
    return std::make_unique<BvhAccelerator<Layout>>(makeBuilder(env), settings.build, settings.traversal,
                                                    settings.stats, settings.update);
}

std::vector<AcceleratorInfo> bvhInfos(const std::string& name, const std::string& description,
                                      std::vector<std::string> keys, const std::vector<int>& wideLayouts,
                                      const BuilderMaker& makeBuilder) {
    bvhCommonKeys().appendNames(keys);
    std::vector<AcceleratorInfo> infos = {
        {name,
         description,
         keys,
         [makeBuilder](const Env& env) { return makeBvhAccelerator<BinaryBvh>(makeBuilder, env); },
         {}}};
    for (int width : wideLayouts) {
        auto create = [makeBuilder, width](const Env& env) {
            return width == 4 ? makeBvhAccelerator<WideBvh<4>>(makeBuilder, env)
                              : makeBvhAccelerator<WideBvh<8>>(makeBuilder, env);
        };
        infos.push_back({name + std::to_string(width), wideDescription(name, width), keys, create, {}});
    }
    return infos;
}

// bvhlab's own: brute force, Embree, and the accelerators of each builder of the table.
std::vector<AcceleratorInfo> ownInfos() {
    std::vector<std::string> embreeKeyNames;
    embreeKeys().appendNames(embreeKeyNames);
    std::vector<AcceleratorInfo> infos = {
        {"naive",
         "brute force: tests every triangle; the reference the others are tested against",
         {},
         [](const Env&) { return std::make_unique<NaiveAccelerator>(); },
         {}},
        {"embree",
         "Intel Embree 3 (rtcIntersect1/rtcOccluded1): the speed reference; no counters, no visible tree",
         embreeKeyNames,
         [](const Env& env) { return std::make_unique<EmbreeAccelerator>(env); },
         {}},
    };
    for (const BuilderTableEntry& entry : bvhBuilderTable()) {
        const BuilderRecord& builder = entry.builder;
        std::vector<std::string> keys;
        for (const BvhKeys* own : entry.keys) own->appendNames(keys);
        for (AcceleratorInfo& info : bvhInfos(builder.name, entry.description, keys, entry.wideLayouts,
                                              [&builder](const Env&) { return builder; }))
            infos.push_back(std::move(info));
    }
    return infos;
}

std::vector<AcceleratorInfo>& registeredInfos() {
    static std::vector<AcceleratorInfo> infos = ownInfos();
    return infos;
}

}  // namespace

const std::vector<AcceleratorInfo>& acceleratorInfos() { return registeredInfos(); }

const AcceleratorInfo* findAccelerator(const std::string& name) {
    for (const AcceleratorInfo& info : registeredInfos())
        if (info.name == name) return &info;
    return nullptr;
}

std::unique_ptr<Accelerator> guardLikeAPlugin(std::unique_ptr<Accelerator> inner, const std::string& plugin,
                                              const std::string& name) {
    return guardAccelerator(std::move(inner), plugin, name);
}

void addAccelerator(AcceleratorInfo info) {
    if (const AcceleratorInfo* taken = findAccelerator(info.name))
        throw InputError(fmt::format("{}: accelerator '{}' is already defined by {}", info.plugin, info.name,
                                     taken->plugin.empty() ? "bvhlab" : taken->plugin));
    info.create = [create = std::move(info.create), plugin = info.plugin, name = info.name](const Env& env) {
        std::unique_ptr<Accelerator> accel = guardPlugin(plugin, name, "its factory", [&] { return create(env); });
        if (!accel)
            throw PluginError(fmt::format("plugin {}, accelerator '{}': its factory returned nothing", plugin, name));
        return guardAccelerator(std::move(accel), plugin, name);
    };
    registeredInfos().push_back(std::move(info));
}

void addBvhBuilder(const LoadedBuilder& builder, const std::string& description, const std::string& plugin) {
    for (AcceleratorInfo& info : bvhInfos(builder.name, description, builder.keys, {4, 8},
                                          [builder](const Env& env) { return pluginBuilderRecord(builder, env); })) {
        info.plugin = plugin;
        addAccelerator(std::move(info));
    }
}

void registerAcceleratorKeys(EnvRegistry& registry) {
    std::vector<std::string> names;
    for (const AcceleratorInfo& info : acceleratorInfos()) names.push_back(info.name);
    registry.add(keys::ASDS::type.declaration(names));
    registry.add(keys::ASDS::plugins);
    embreeKeys().registerWith(registry);
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
