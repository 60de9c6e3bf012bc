// Opening a plugin file (docs/plugins.md): a shared library whose entry point (<bvhlab/plugin.h>)
// adds accelerators and builders with their keys. Its ABI is checked before anything of it is
// called, and what its entry point adds is checked in itself (names, keys, builders' functions)
// and returned; the caller registers it where it belongs (apps/runtime/plugins.h).
#pragma once

#include "accel/plugins/plugin_additions.h"

#include <bvhlab/plugin.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace bvhlab {

// Closes a plugin file (dlclose).
struct CloseLibrary {
    void operator()(void* library) const;
};

// What a plugin file holds: how it was built and what its entry point added.
struct OpenedPlugin {
    std::filesystem::path file;  // absolute
    std::string abi;             // the fingerprint of its ABI (<bvhlab/abi.h>), bvhlab's own
    std::string compiler;        // PluginBuildInfo
    std::string cxxFlags;        // empty when not recorded (a plugin built without bvhlab_add_plugin)
    bool optimized = false;
    PluginAdditions additions;  // what its entry point added

    // The open file: closed when this is dropped, unless released once what the plugin adds is
    // registered (its code must then stay loaded for the life of the process).
    std::unique_ptr<void, CloseLibrary> library;
};

// Opens `file` (absolute) and asks its entry point what it adds. Throws InputError naming the file when it cannot be
// opened, is not a bvhlab plugin, was built against another ABI (both fingerprints and where they differ named), its
// entry point throws (a key not well declared among them), or what it adds is malformed
// (checkAdditions, plugin_additions.h). On a refusal the file is closed.
OpenedPlugin openPlugin(const std::filesystem::path& file);

// A hash of an ABI's figures, to name it in one word: 16 hex digits.
std::string abiFingerprint(View<const AbiFigure> figures);

// Why a plugin whose ABI is `plugin` cannot be loaded into this bvhlab, or "" when it can: both
// fingerprints and the figures in which they differ.
std::string abiMismatch(View<const AbiFigure> plugin);

}  // namespace bvhlab
