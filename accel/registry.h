// Creates accelerators by name. `ASDS::type` in env chooses one. An accelerator of bvhlab's own
// is an entry in registry.cpp besides its folder and library, a BVH builder an entry in
// accel/bvh/builder_table.cpp besides its file (docs/adding-an-accelerator.md lists every file).
#pragma once

#include "accel/plugins/plugin_builder.h"
#include "framework/config/env.h"
#include "framework/core/accelerator.h"

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

// Adds a plugin's accelerator (info.plugin set). Its build and queries are guarded: an exception
// thrown inside reaches the caller as a PluginError naming the plugin and the accelerator.
// Throws InputError if the name is taken.
void addAccelerator(AcceleratorInfo info);

// `inner` behind the guard every plugin's accelerator is called through, as if `plugin` had
// added it: for measuring what the guard costs (bvhlab bench's nothing-guarded row).
std::unique_ptr<Accelerator> guardLikeAPlugin(std::unique_ptr<Accelerator> inner, const std::string& plugin,
                                              const std::string& name);

// Adds a plugin's builder as the accelerators NAME, NAME4 and NAME8 (accel/plugins/plugin_builder.h),
// described by `description` and guarded as addAccelerator's are.
void addBvhBuilder(const LoadedBuilder& builder, const std::string& description, const std::string& plugin);

// Throws InputError naming the unknown accelerator and the known ones.
std::unique_ptr<Accelerator> createAccelerator(const std::string& name, const Env& env);
inline std::unique_ptr<Accelerator> createAccelerator(const Env& env) {
    return createAccelerator(env.get(keys::ASDS::type), env);
}

// ASDS::type, ASDS::plugins and the keys of bvhlab's own accelerators (a plugin's are
// registered when it is loaded).
void registerAcceleratorKeys(EnvRegistry& registry);

}  // namespace bvhlab
