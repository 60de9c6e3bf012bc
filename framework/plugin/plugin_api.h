// The plugin API: what a shared library needs to add acceleration structures to bvhlab at run
// time (docs/plugins.md). A plugin defines its entry point with BVHLAB_PLUGIN(registrar) and adds
// one or more accelerators, or builders (builder_api.h), to the registrar. It compiles against
// the installed headers (the accelerator interface, rays, hits, counters, primitives and their
// watertight tests, typed env keys) and links bvhlab::plugin_api, which carries the
// floating-point flags those tests need.
#pragma once

#include "framework/config/env.h"
#include "framework/core/accelerator.h"
#include "framework/plugin/builder_api.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

// Raised when anything a plugin compiles against changes shape; a plugin built for another
// version is refused at load time with both versions named. 2: BuildStats::figures. 3: build()
// returns nothing and is timed by bvhlab; statistics() reports the tree; BuildStats::buildCpuMs
// is a double; builders (builder_api.h).
#define BVHLAB_PLUGIN_API_VERSION 3

namespace bvhlab {

// One accelerator a plugin adds: chosen by `ASDS::type name`, described in `bvhlab keys`, its
// own env keys declared as bvhlab's are (`inline constexpr IntKey ...; key.declaration()`).
struct PluginAccelerator {
    std::string name;
    std::string description;
    std::vector<EnvKey> keys;
    std::function<std::unique_ptr<Accelerator>(const Env&)> create;
};

// What the entry point is given. An interface (no symbol of bvhlab's to link against).
class PluginRegistrar {
public:
    virtual ~PluginRegistrar() = default;
    virtual void addAccelerator(PluginAccelerator accelerator) = 0;
    virtual void addBuilder(PluginBuilder builder) = 0;
};

}  // namespace bvhlab

// The two symbols bvhlab looks up in a plugin: the API version it was compiled against, then
// the registration function, called once when the plugin is loaded.
#define BVHLAB_PLUGIN_EXPORT extern "C" __attribute__((visibility("default")))
#define BVHLAB_PLUGIN(registrar)                                                       \
    BVHLAB_PLUGIN_EXPORT int bvhlab_plugin_api_version() { return BVHLAB_PLUGIN_API_VERSION; } \
    BVHLAB_PLUGIN_EXPORT void bvhlab_register_plugin(bvhlab::PluginRegistrar& registrar)
