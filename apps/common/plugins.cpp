#include "apps/common/plugins.h"

#include "accel/registry.h"
#include "apps/common/program_keys.h"
#include "framework/core/error.h"
#include "framework/plugin/plugin_api.h"
#include "framework/report/provenance.h"
#include "framework/scene/scene_cache.h"

#include <dlfcn.h>
#include <fmt/format.h>
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

class Registrar final : public PluginRegistrar {
public:
    void addAccelerator(PluginAccelerator accelerator) override { added.push_back(std::move(accelerator)); }
    std::vector<PluginAccelerator> added;
};

// What a plugin adds, checked before any of it is registered.
void checkAdditions(const std::string& plugin, const std::vector<PluginAccelerator>& added) {
    if (added.empty()) throw InputError(fmt::format("{}: the plugin adds no accelerator", plugin));
    std::vector<std::string> names, keyNames;
    for (const PluginAccelerator& a : added) {
        if (a.name.empty() || a.name.find_first_of(" \t,:=") != std::string::npos)
            throw InputError(fmt::format("{}: accelerator name '{}' must be one word without , : or =", plugin, a.name));
        if (!a.create) throw InputError(fmt::format("{}: accelerator '{}' has no factory", plugin, a.name));
        if (const AcceleratorInfo* taken = findAccelerator(a.name); taken || std::count(names.begin(), names.end(), a.name))
            throw InputError(fmt::format("{}: accelerator '{}' is already defined by {}", plugin, a.name,
                                         taken && !taken->plugin.empty() ? taken->plugin
                                         : taken                         ? "bvhlab"
                                                                         : "this plugin"));
        names.push_back(a.name);
        for (const EnvKey& key : a.keys) {
            if (key.name.find("::") == std::string::npos)
                throw InputError(fmt::format("{}: env key '{}' of '{}' is not 'Section::key'", plugin, key.name, a.name));
            if (programKeys().find(key.name) || std::count(keyNames.begin(), keyNames.end(), key.name))
                throw InputError(fmt::format("{}: env key '{}' of '{}' is already declared", plugin, key.name, a.name));
            keyNames.push_back(key.name);
        }
    }
}

}  // namespace

const std::deque<LoadedPlugin>& loadedPlugins() { return pluginList(); }

const LoadedPlugin& loadPlugin(const std::filesystem::path& given) {
    std::error_code ec;
    const std::filesystem::path file = std::filesystem::weakly_canonical(std::filesystem::absolute(given), ec);
    for (const LoadedPlugin& p : pluginList())
        if (p.file == file) return p;
    if (!std::filesystem::is_regular_file(file)) throw inputError(given, 0, "plugin file not found");
    const std::string name = file.string();

    void* library = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library) throw inputError(given, 0, fmt::format("cannot load as a plugin: {}", dlerror()));
    auto refuse = [&](const std::string& why) {
        dlclose(library);
        return inputError(given, 0, why);
    };
    using VersionFunction = int (*)();
    using RegisterFunction = void (*)(PluginRegistrar&);
    const auto version = reinterpret_cast<VersionFunction>(dlsym(library, "bvhlab_plugin_api_version"));
    const auto registerPlugin = reinterpret_cast<RegisterFunction>(dlsym(library, "bvhlab_register_plugin"));
    if (!version || !registerPlugin)
        throw refuse("not a bvhlab plugin: it does not export bvhlab_plugin_api_version and bvhlab_register_plugin "
                     "(define them with BVHLAB_PLUGIN, docs/plugins.md)");
    const int apiVersion = version();
    if (apiVersion != BVHLAB_PLUGIN_API_VERSION)
        throw refuse(fmt::format("built for plugin API version {}, but this bvhlab has version {}: rebuild it "
                                 "against this bvhlab (docs/plugins.md)",
                                 apiVersion, BVHLAB_PLUGIN_API_VERSION));
    Registrar registrar;
    try {
        registerPlugin(registrar);
    } catch (const std::exception& e) {
        throw refuse(fmt::format("its entry point threw: {}", e.what()));
    } catch (...) {
        throw refuse("its entry point threw an exception that is not a std::exception");
    }
    checkAdditions(name, registrar.added);

    const SceneCacheKey checksum = sceneCacheKey(file);
    LoadedPlugin plugin{file, checksum.size, checksum.crc32, apiVersion, {}};
    std::vector<EnvKey> keys;
    for (PluginAccelerator& a : registrar.added) {
        std::vector<std::string> keyNames;
        for (EnvKey& key : a.keys) {
            keyNames.push_back(key.name);
            keys.push_back(std::move(key));
        }
        plugin.accelerators.push_back(a.name);
        addAccelerator({a.name, std::move(a.description), std::move(keyNames), std::move(a.create), name});
    }
    registerPluginKeys(name, keys);
    recordLoadedPlugin({{"path", name},
                                 {"size", plugin.size},
                                 {"crc32", fmt::format("{:08x}", plugin.crc32)},
                                 {"api_version", plugin.apiVersion},
                                 {"accelerators", plugin.accelerators}});
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
    std::error_code ec;
    const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        folders.push_back(program.parent_path() / "plugins");
        folders.push_back((program.parent_path() / ".." / "lib" / "bvhlab" / "plugins").lexically_normal());
    }
    return folders;
}

bool loadPluginFor(const std::string& accelerator) {
    if (findAccelerator(accelerator)) return true;
    if (accelerator.empty() || accelerator.find('/') != std::string::npos) return false;
    for (const std::filesystem::path& folder : pluginFolders()) {
        const std::filesystem::path file = folder / (accelerator + ".so");
        std::error_code ec;
        if (!std::filesystem::is_regular_file(file, ec)) continue;
        loadPlugin(file);
        return findAccelerator(accelerator) != nullptr;
    }
    return false;
}

}  // namespace bvhlab
