// The plugin API: what a shared library needs to add acceleration structures to bvhlab at run
// time (docs/plugins.md). A plugin defines its entry point with BVHLAB_PLUGIN(registrar) and adds
// one or more accelerators, or builders (<bvhlab/builder.h>), to the registrar. It compiles
// against these headers alone (the accelerator interface, rays, hits, counters, primitives and
// their watertight tests, its own keys) and links bvhlab::plugin_api, which carries the
// floating-point flags those tests need; it links nothing of bvhlab's.
#pragma once

#include <bvhlab/abi.h>
#include <bvhlab/accelerator.h>
#include <bvhlab/builder.h>
#include <bvhlab/registrar.h>
#include <bvhlab/settings.h>

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
#define BVHLAB_PLUGIN_COMPILER \
    "Clang " BVHLAB_PLUGIN_COMPILER_VERSION(__clang_major__, __clang_minor__, __clang_patchlevel__)
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

// The three symbols bvhlab looks up in a plugin: the ABI it was compiled against (<bvhlab/abi.h>),
// how it was compiled, then the registration function, called once when the plugin is loaded.
#define BVHLAB_PLUGIN_EXPORT extern "C" __attribute__((visibility("default")))
#define BVHLAB_PLUGIN(registrar)                                                                       \
    BVHLAB_PLUGIN_EXPORT const bvhlab::AbiFigure* bvhlab_plugin_abi(size_t* count) {                   \
        const bvhlab::View<const bvhlab::AbiFigure> figures = bvhlab::abiFigures();                    \
        *count = figures.size();                                                                       \
        return figures.data();                                                                         \
    }                                                                                                  \
    BVHLAB_PLUGIN_EXPORT const bvhlab::PluginBuildInfo* bvhlab_plugin_build_info() {                   \
        static constexpr bvhlab::PluginBuildInfo info{BVHLAB_PLUGIN_COMPILER, BVHLAB_PLUGIN_OPTIMIZED, \
                                                      BVHLAB_PLUGIN_CXX_FLAGS};                        \
        return &info;                                                                                  \
    }                                                                                                  \
    BVHLAB_PLUGIN_EXPORT void bvhlab_register_plugin(bvhlab::PluginRegistrar& registrar)
