#include "accel/registry.h"

#include "accel/twolevel/two_level_accelerator.h"

#include "accel/bvh/builder_table.h"
#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/bvh_env.h"
#include "accel/embree/embree_accelerator.h"
#include "accel/embree/embree_instances.h"
#include "accel/naive/naive_accelerator.h"
#include "accel/plugins/guarded_accelerator.h"
#include "accel/plugins/plugin_builder.h"
#include "framework/config/plugin_settings.h"
#include "framework/core/error.h"

#include <fmt/ranges.h>

namespace bvhlab {

namespace {

// bvhlab's own accelerators, added through the registrar a plugin's entry point is given.
void addOwnAccelerators(PluginRegistrar& registrar) {
    registrar.addAccelerator({"naive",
                              "brute force: tests every triangle; the reference the others are tested against",
                              {},
                              [](const PluginSettings&) -> Accelerator* { return new NaiveAccelerator(); }});
    const PluginKeyList embreeKeys(embreeKeyDeclarations());
    registrar.addAccelerator(
        {"embree", "Intel Embree 3 (rtcIntersect1/rtcOccluded1): the speed reference; no counters, no visible tree",
         embreeKeys.view(),
         [](const PluginSettings& keys) -> Accelerator* { return new EmbreeAccelerator(EmbreeConfig::from(keys)); }});
    addBvhAccelerators(registrar);
}

const PluginAdditions& ownAdditions() {
    static const PluginAdditions additions = [] {
        RecordingRegistrar registrar;
        addOwnAccelerators(registrar);
        checkAdditions("bvhlab", registrar.additions);
        return std::move(registrar.additions);
    }();
    return additions;
}

std::vector<std::string> namesOf(const std::vector<EnvKey>& keys) {
    std::vector<std::string> names;
    for (const EnvKey& key : keys) names.push_back(key.name);
    return names;
}

// An accelerator as the registry keeps it: made with the values of its keys in the run's env.
AcceleratorInfo infoOf(const PluginAcceleratorEntry& a, const std::string& plugin) {
    std::vector<std::string> keyNames = namesOf(a.keys);
    auto create = [create = a.create, keyNames, name = a.name](const Env& env) {
        const EnvPluginSettings settings(env, keyNames, fmt::format("accelerator '{}'", name));
        return std::unique_ptr<Accelerator>(create(settings));
    };
    return {a.name, a.description, std::move(keyNames), std::move(create), plugin};
}

// A plugin's builder over one layout: its own keys, and those every BVH accelerator reads.
template <typename Layout>
std::unique_ptr<Accelerator> makePluginBvh(const LoadedBuilder& builder, const std::vector<std::string>& keyNames,
                                           const Env& env) {
    const EnvPluginSettings keys(env, keyNames, fmt::format("builder '{}'", builder.name));
    const BvhSettings settings = bvhSettings(keys, {});
    return std::make_unique<BvhAccelerator<Layout>>(pluginBuilderRecord(builder, env), settings.build,
                                                    settings.traversal, settings.stats, settings.update);
}

std::vector<AcceleratorInfo> builderInfos(const PluginBuilderEntry& b, const std::string& plugin) {
    std::vector<std::string> keyNames = b.builder.keys;
    for (std::string& key : namesOf(bvhKeyDeclarations({}))) keyNames.push_back(std::move(key));
    const LoadedBuilder& builder = b.builder;
    return {
        {builder.name, b.description, keyNames,
         [builder, keyNames](const Env& env) { return makePluginBvh<BinaryBvh>(builder, keyNames, env); }, plugin},
        {builder.name + "4", wideBvhDescription(builder.name, 4), keyNames,
         [builder, keyNames](const Env& env) { return makePluginBvh<WideBvh<4>>(builder, keyNames, env); }, plugin},
        {builder.name + "8", wideBvhDescription(builder.name, 8), keyNames,
         [builder, keyNames](const Env& env) { return makePluginBvh<WideBvh<8>>(builder, keyNames, env); }, plugin},
    };
}

std::vector<AcceleratorInfo>& registeredInfos() {
    static std::vector<AcceleratorInfo> infos = [] {
        std::vector<AcceleratorInfo> own;
        for (const PluginAcceleratorEntry& a : ownAdditions().accelerators) own.push_back(infoOf(a, {}));
        return own;
    }();
    return infos;
}

// A plugin's accelerator behind the guard: its factory's and its calls' exceptions become
// PluginErrors naming it.
AcceleratorInfo guarded(AcceleratorInfo info) {
    info.create = [create = std::move(info.create), plugin = info.plugin, name = info.name](const Env& env) {
        std::unique_ptr<Accelerator> accel = guardPlugin(plugin, name, "its factory", [&] { return create(env); });
        if (!accel)
            throw PluginError(fmt::format("plugin {}, accelerator '{}': its factory returned nothing", plugin, name));
        return guardAccelerator(std::move(accel), plugin, name);
    };
    return info;
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

void addPluginAccelerators(const PluginAdditions& additions, const std::string& plugin) {
    for (const std::string& name : additions.acceleratorNames())
        if (const AcceleratorInfo* taken = findAccelerator(name))
            throw InputError(fmt::format("{}: accelerator '{}' is already defined by {}", plugin, name,
                                         taken->plugin.empty() ? "bvhlab" : taken->plugin));
    for (const PluginAcceleratorEntry& a : additions.accelerators)
        registeredInfos().push_back(guarded(infoOf(a, plugin)));
    for (const PluginBuilderEntry& b : additions.builders)
        for (AcceleratorInfo& info : builderInfos(b, plugin)) registeredInfos().push_back(guarded(std::move(info)));
}

void registerAcceleratorKeys(EnvRegistry& registry) {
    std::vector<std::string> names;
    for (const AcceleratorInfo& info : acceleratorInfos()) names.push_back(info.name);
    registry.add(keys::ASDS::type.declaration(names));
    registry.add(keys::ASDS::plugins);
    for (EnvKey& key : ownAdditions().keys()) registry.add(std::move(key));
}

namespace {

// Throws InputError naming the unknown accelerator and the known ones.
const AcceleratorInfo& acceleratorNamed(const std::string& name) {
    if (const AcceleratorInfo* info = findAccelerator(name)) return *info;
    std::vector<std::string> names;
    for (const AcceleratorInfo& info : acceleratorInfos()) names.push_back(info.name);
    throw InputError(fmt::format("unknown accelerator '{}' (known: {})", name, fmt::join(names, ", ")));
}

}  // namespace

std::unique_ptr<Accelerator> createAccelerator(const std::string& name, const Env& env) {
    return acceleratorNamed(name).create(env);
}

std::unique_ptr<InstancedAccelerator> createInstanced(std::vector<Instance> instances, const std::string& bottom,
                                                      const Env& env) {
    if (bottom == "embree") return std::make_unique<EmbreeInstances>(std::move(instances), EmbreeConfig::fromEnv(env));
    auto create = acceleratorNamed(bottom).create;
    auto values = std::make_shared<const Env>(env);
    return std::make_unique<TwoLevelAccelerator>(
        std::move(instances), [create, values] { return create(*values); }, bvhSettingsFromEnv(env).build);
}

}  // namespace bvhlab
