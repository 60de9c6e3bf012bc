// Loading plugins into the program (docs/plugins.md): the file opened by the plugin loader
// (accel/plugins/plugin_loader.h), what it adds registered with the registry and its keys with
// the program's, the plugin recorded in the provenance. A plugin is loaded from --plugin FILE,
// from ASDS::plugins in an env layer, or found by the name of the accelerator asked for
// (`-DASDS::type=NAME` loads NAME.so from the plugin folders).
#pragma once

#include <cstdint>
#include <deque>
#include <filesystem>
#include <string>
#include <vector>

namespace bvhlab {

struct LoadedPlugin {
    std::filesystem::path file;  // absolute
    uint64_t size = 0;
    uint32_t crc32 = 0;
    std::string abi;  // the fingerprint of the ABI it was built against (<bvhlab/abi.h>)
    std::vector<std::string> accelerators;
    // How it was compiled (PluginBuildInfo, <bvhlab/abi.h>).
    std::string compiler;
    std::string cxxFlags;  // empty when not recorded (a plugin built without bvhlab_add_plugin)
    bool optimized = false;
};

// Loads `file` once (again: nothing happens). Throws InputError naming the file when it cannot be
// opened, is not a bvhlab plugin, was built against another ABI (both named), its entry
// point throws, or it adds an accelerator or key that exists already (then it adds nothing).
// Warns on stderr, naming the file, when the plugin was compiled without optimisation.
const LoadedPlugin& loadPlugin(const std::filesystem::path& file);
const std::deque<LoadedPlugin>& loadedPlugins();  // in load order

// Where plugins are found by name, in order: the folders of BVHLAB_PLUGIN_PATH (':'-separated),
// then bvhlab's own (build/plugins in a build tree, PREFIX/lib/bvhlab/plugins when installed).
std::vector<std::filesystem::path> pluginFolders();

// If `accelerator` is not known, loads `accelerator`.so from the first plugin folder holding
// one, or for NAME4 and NAME8 (a builder's wide layouts) NAME.so. False when it is still unknown
// (the caller then reports it with unknownAcceleratorMessage). Throws InputError naming both
// files when the one found on BVHLAB_PLUGIN_PATH has the name of one bvhlab ships.
bool loadPluginFor(const std::string& accelerator);

// Loads every NAME.so of the plugin folders as loadPluginFor(NAME) finds it, so that a listing
// (`bvhlab keys`, bvhlab.accelerators()) shows what the commands would load by name. One that
// does not load is left out with a warning on stderr saying why.
void loadPluginsOfFolders();

// Why `accelerator` is unknown after loadPluginFor: the folders searched, what a file of its name
// found there adds instead, and the names that are known.
std::string unknownAcceleratorMessage(const std::string& accelerator);

// Throws InputError when `key` (set at `origin`) is not a known key and its section is none of
// bvhlab's: the key of a plugin that is not loaded, named so, with the ways to load one.
void checkKeyIsNotAnUnloadedPlugins(const std::string& key, const std::string& origin);

}  // namespace bvhlab
