#include "apps/runtime/plugins.h"

#include "accel/plugins/plugin_loader.h"
#include "accel/registry.h"
#include "apps/runtime/program_keys.h"
#include "framework/config/install_paths.h"
#include "framework/core/error.h"
#include "framework/report/provenance.h"
#include "framework/scene/scene_cache.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <deque>

namespace bvhlab {
namespace {

// Plugins stay loaded until the process ends: their accelerators' code lives in them.
std::deque<LoadedPlugin>& pluginList() {
    static std::deque<LoadedPlugin> list;
    return list;
}

// What `plugin` adds must be new to the run: checked before any of it is registered.
void checkIsNew(const OpenedPlugin& plugin) {
    const std::string file = plugin.file.string();
    for (const std::string& name : plugin.additions.acceleratorNames())
        if (const AcceleratorInfo* taken = findAccelerator(name))
            throw InputError(fmt::format("{}: accelerator '{}' is already defined by {}", file, name,
                                         taken->plugin.empty() ? "bvhlab" : taken->plugin));
    for (const EnvKey& key : plugin.additions.keys())
        if (programKeys().find(key.name))
            throw InputError(fmt::format("{}: env key '{}' is already declared", file, key.name));
}

}  // namespace

const std::deque<LoadedPlugin>& loadedPlugins() { return pluginList(); }

const LoadedPlugin& loadPlugin(const std::filesystem::path& given) {
    std::error_code ec;
    const std::filesystem::path file = std::filesystem::weakly_canonical(std::filesystem::absolute(given), ec);
    for (const LoadedPlugin& p : pluginList())
        if (p.file == file) return p;
    if (!std::filesystem::is_regular_file(file)) throw inputError(given, 0, "plugin file not found");

    OpenedPlugin opened = openPlugin(file);
    checkIsNew(opened);
    addPluginAccelerators(opened.additions, file.string());
    registerPluginKeys(file.string(), opened.additions.keys());
    opened.library.release();  // its code is now the registry's

    const SceneCacheKey checksum = sceneCacheKey(file);
    LoadedPlugin plugin{file,
                        checksum.size,
                        checksum.crc32,
                        opened.abi,
                        opened.additions.acceleratorNames(),
                        opened.compiler,
                        opened.cxxFlags,
                        opened.optimized};
    recordLoadedPlugin({{"path", file.string()},
                        {"size", plugin.size},
                        {"crc32", fmt::format("{:08x}", plugin.crc32)},
                        {"abi", plugin.abi},
                        {"accelerators", plugin.accelerators},
                        {"compiler", plugin.compiler},
                        {"cxx_flags", plugin.cxxFlags},
                        {"optimized", plugin.optimized}});
    if (!plugin.optimized)
        fmt::print(stderr,
                   "warning: plugin {} was compiled without optimisation (flags: {}): its times are not "
                   "representative; rebuild it with -DCMAKE_BUILD_TYPE=Release (docs/plugins.md)\n",
                   file.string(), plugin.cxxFlags.empty() ? "not recorded" : plugin.cxxFlags);
    pluginList().push_back(std::move(plugin));
    return pluginList().back();
}

std::vector<std::filesystem::path> pluginFolders() {
    std::vector<std::filesystem::path> folders;
    if (const char* path = std::getenv("BVHLAB_PLUGIN_PATH")) {
        std::string list = path;
        for (size_t start = 0; start <= list.size();) {
            const size_t end = std::min(list.find(':', start), list.size());
            if (end > start) folders.emplace_back(list.substr(start, end - start));
            start = end + 1;
        }
    }
    folders.push_back(bundledPluginFolder());
    return folders;
}

namespace {

// The files loadPluginFor looks for: NAME.so, and NAME.so for NAME4 and NAME8 (a builder's wide layouts).
std::vector<std::string> pluginFilesFor(const std::string& accelerator) {
    std::vector<std::string> files = {accelerator + ".so"};
    if (accelerator.size() > 1 && (accelerator.ends_with('4') || accelerator.ends_with('8')))
        files.push_back(accelerator.substr(0, accelerator.size() - 1) + ".so");
    return files;
}

std::string pluginFolderList() {
    std::vector<std::string> folders;
    for (const std::filesystem::path& folder : pluginFolders()) folders.push_back(folder.string());
    return fmt::format("{}; BVHLAB_PLUGIN_PATH adds folders", fmt::join(folders, ", "));
}

}  // namespace

std::string unknownAcceleratorMessage(const std::string& accelerator) {
    std::vector<std::string> known;
    for (const AcceleratorInfo& info : acceleratorInfos()) known.push_back(info.name);
    for (const std::string& file : pluginFilesFor(accelerator))
        for (const LoadedPlugin& plugin : pluginList())
            if (plugin.file.filename() == file)
                return fmt::format(
                    "unknown accelerator '{}': the plugin {} was loaded for it, but it adds {}, not '{}'", accelerator,
                    plugin.file.string(), fmt::join(plugin.accelerators, ", "), accelerator);
    return fmt::format(
        "unknown accelerator '{}': none of bvhlab's, no plugin loaded adds it, and no {} in the plugin "
        "folders ({}). Known: {}",
        accelerator, fmt::join(pluginFilesFor(accelerator), " or "), pluginFolderList(), fmt::join(known, ", "));
}

void checkKeyIsNotAnUnloadedPlugins(const std::string& key, const std::string& origin) {
    const size_t colons = key.find("::");
    if (programKeys().find(key) || colons == std::string::npos) return;  // a key without a section: Env says so
    const std::string section = key.substr(0, colons + 2);
    for (const auto& [name, declared] : programKeys().keys())
        if (name.starts_with(section)) return;  // a misspelt key of a known section: Env says "did you mean"
    throw InputError(
        fmt::format("{}: unknown key '{}': no section {} in bvhlab or a loaded plugin. If it is a "
                    "plugin's key, load the plugin: --plugin FILE, ASDS::plugins FILE in an env file, "
                    "or name its accelerator (--accel NAME, ASDS::type NAME) to load NAME.so from the "
                    "plugin folders ({})",
                    origin, key, section, pluginFolderList()));
}

bool loadPluginFor(const std::string& accelerator) {
    if (findAccelerator(accelerator)) return true;
    if (accelerator.empty() || accelerator.find('/') != std::string::npos) return false;
    for (const std::string& file : pluginFilesFor(accelerator))
        for (const std::filesystem::path& folder : pluginFolders()) {
            const std::filesystem::path path = folder / file, shipped = bundledPluginFolder() / file;
            std::error_code ec;
            if (!std::filesystem::is_regular_file(path, ec)) continue;
            // A user's file named as one bvhlab ships would replace it unseen: only --plugin may.
            if (std::filesystem::is_regular_file(shipped, ec) && !std::filesystem::equivalent(path, shipped, ec))
                throw InputError(
                    fmt::format("{} (on BVHLAB_PLUGIN_PATH) has the name of a plugin bvhlab ships, {}: "
                                "which one '{}' means is not clear. Rename yours, or load it with "
                                "--plugin {} (or ASDS::plugins) to use it instead of bvhlab's",
                                path.string(), shipped.string(), accelerator, path.string()));
            loadPlugin(path);
            return findAccelerator(accelerator) != nullptr;
        }
    return false;
}

void loadPluginsOfFolders() {
    for (const std::filesystem::path& folder : pluginFolders()) {
        std::error_code ec;
        std::vector<std::filesystem::path> files;
        for (const auto& entry : std::filesystem::directory_iterator(folder, ec))
            if (entry.path().extension() == ".so") files.push_back(entry.path());
        std::sort(files.begin(), files.end());
        for (const std::filesystem::path& file : files) {
            try {
                loadPluginFor(file.stem().string());
            } catch (const InputError& notLoaded) {
                fmt::print(stderr, "warning: {} is not listed: {}\n", file.string(), notLoaded.what());
            }
        }
    }
}

}  // namespace bvhlab
