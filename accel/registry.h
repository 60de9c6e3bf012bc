// Creates accelerators by name. `ASDS::type` in env chooses one. Every accelerator comes through
// the registrar a plugin's entry point is given (<bvhlab/registrar.h>), bvhlab's own too
// (registry.cpp): an accelerator of bvhlab's is a call there besides its folder and library, a
// BVH builder an entry in accel/bvh/builder_table.cpp besides its file
// (docs/adding-an-accelerator.md lists every file).
#pragma once

#include "accel/plugins/plugin_additions.h"
#include "framework/config/env.h"
#include "framework/core/accelerator.h"
#include "framework/core/instanced_accelerator.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace bvhlab {

namespace keys::ASDS {
// Its choices, the accelerators' names, are given when it is registered.
inline constexpr ChoiceKey type{"ASDS::type", "sahbvh8", {}, "acceleration structure to build and trace with"};
inline constexpr TextKey plugins{"ASDS::plugins", "",
                                 "plugin files to load, comma-separated (relative to the env file's folder); "
                                 "docs/plugins.md"};
}  // namespace keys::ASDS

struct AcceleratorInfo {
    std::string name;
    std::string description;
    std::vector<std::string> envKeys;  // the keys it reads, besides the framework's
    std::function<std::unique_ptr<Accelerator>(const Env&)> create;
    std::string plugin;  // the plugin file it comes from; empty for bvhlab's own
};

// bvhlab's own accelerators, then those plugins added, in load order.
const std::vector<AcceleratorInfo>& acceleratorInfos();
const AcceleratorInfo* findAccelerator(const std::string& name);

// Adds what a plugin's entry point added (`plugin`: its file): its accelerators, and the
// accelerators NAME, NAME4 and NAME8 of each of its builders (accel/plugins/plugin_builder.h).
// Their builds and queries are guarded: an exception thrown inside reaches the caller as a
// PluginError naming the plugin and the accelerator. Throws InputError if a name is taken (then
// it adds nothing).
void addPluginAccelerators(const PluginAdditions& additions, const std::string& plugin);

// `inner` behind the guard every plugin's accelerator is called through, as if `plugin` had
// added it: for measuring what the guard costs (bvhlab bench's nothing-guarded row).
std::unique_ptr<Accelerator> guardLikeAPlugin(std::unique_ptr<Accelerator> inner, const std::string& plugin,
                                              const std::string& name);

// Throws InputError naming the unknown accelerator and the known ones.
std::unique_ptr<Accelerator> createAccelerator(const std::string& name, const Env& env);
inline std::unique_ptr<Accelerator> createAccelerator(const Env& env) {
    return createAccelerator(env.get(keys::ASDS::type), env);
}

// Two levels over `instances`. With `bottom` "embree", Embree's own instancing (EmbreeInstances,
// configured by the env's Embree:: keys); otherwise ours (TwoLevelAccelerator): each instance's
// structure the accelerator `bottom` made with the env's values, under our top level built by
// binned SAH with the env's BVH:: keys. Throws as createAccelerator does for an unknown `bottom`.
std::unique_ptr<InstancedAccelerator> createInstanced(std::vector<Instance> instances, const std::string& bottom,
                                                      const Env& env);

// ASDS::type, ASDS::plugins and the keys of bvhlab's own accelerators (a plugin's are
// registered when it is loaded).
void registerAcceleratorKeys(EnvRegistry& registry);

}  // namespace bvhlab
