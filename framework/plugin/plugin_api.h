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

// The shape of everything a plugin compiles against and of the symbols BVHLAB_PLUGIN exports,
// raised when either changes; a plugin built for another version is refused at load time with
// both versions named.
#define BVHLAB_PLUGIN_API_VERSION 5

// How the translation unit that expands BVHLAB_PLUGIN was compiled, as the preprocessor sees it
// there. bvhlab_add_plugin (BvhlabPlugin.cmake) passes the flags of the plugin's build as
// BVHLAB_PLUGIN_CXX_FLAGS; a plugin built another way records none.
#ifndef BVHLAB_PLUGIN_CXX_FLAGS
#define BVHLAB_PLUGIN_CXX_FLAGS ""
#endif
// The compiler as CMake names it and bvhlab's provenance names its own: "GNU 12.2.0".
#define BVHLAB_PLUGIN_STRING(x) #x
#define BVHLAB_PLUGIN_COMPILER_VERSION(major, minor, patch) \
    BVHLAB_PLUGIN_STRING(major) "." BVHLAB_PLUGIN_STRING(minor) "." BVHLAB_PLUGIN_STRING(patch)
#if defined(__clang__)
#define BVHLAB_PLUGIN_COMPILER "Clang " BVHLAB_PLUGIN_COMPILER_VERSION(__clang_major__, __clang_minor__, __clang_patchlevel__)
#elif defined(__GNUC__)
#define BVHLAB_PLUGIN_COMPILER "GNU " BVHLAB_PLUGIN_COMPILER_VERSION(__GNUC__, __GNUC_MINOR__, __GNUC_PATCHLEVEL__)
#else
#define BVHLAB_PLUGIN_COMPILER "unknown"
#endif
#ifdef __OPTIMIZE__
#define BVHLAB_PLUGIN_OPTIMIZED true
#else
#define BVHLAB_PLUGIN_OPTIMIZED false
#endif

namespace bvhlab {

// One accelerator a plugin adds: chosen by `ASDS::type name`, described in `bvhlab keys`, its
// own env keys declared as bvhlab's are (`inline constexpr IntKey ...; key.declaration()`).
struct PluginAccelerator {
    std::string name;
    std::string description;
    std::vector<EnvKey> keys;
    std::function<std::unique_ptr<Accelerator>(const Env&)> create;
};

// How a plugin was compiled, read by bvhlab when it loads the plugin: it warns when the plugin
// is not optimised (its times would not be representative) and records all three in the
// provenance of every run.
struct PluginBuildInfo {
    const char* compiler;  // "GNU 12.2.0"
    bool optimized;        // __OPTIMIZE__ was defined: -O1 or higher, -Os or -Og
    const char* cxxFlags;  // the flags bvhlab_add_plugin recorded; "" for a plugin built otherwise
};

// What the entry point is given. An interface (no symbol of bvhlab's to link against).
class PluginRegistrar {
public:
    virtual ~PluginRegistrar() = default;
    virtual void addAccelerator(PluginAccelerator accelerator) = 0;
    virtual void addBuilder(PluginBuilder builder) = 0;
};

}  // namespace bvhlab

// The three symbols bvhlab looks up in a plugin: the API version it was compiled against, how
// it was compiled, then the registration function, called once when the plugin is loaded.
#define BVHLAB_PLUGIN_EXPORT extern "C" __attribute__((visibility("default")))
#define BVHLAB_PLUGIN(registrar)                                                                   \
    BVHLAB_PLUGIN_EXPORT int bvhlab_plugin_api_version() { return BVHLAB_PLUGIN_API_VERSION; }      \
    BVHLAB_PLUGIN_EXPORT const bvhlab::PluginBuildInfo* bvhlab_plugin_build_info() {                \
        static constexpr bvhlab::PluginBuildInfo info{BVHLAB_PLUGIN_COMPILER, BVHLAB_PLUGIN_OPTIMIZED, \
                                                      BVHLAB_PLUGIN_CXX_FLAGS};                     \
        return &info;                                                                              \
    }                                                                                              \
    BVHLAB_PLUGIN_EXPORT void bvhlab_register_plugin(bvhlab::PluginRegistrar& registrar)
