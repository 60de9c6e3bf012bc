#include "apps/common/plugins.h"

#include "accel/registry.h"
#include "apps/common/program_keys.h"
#include "framework/config/install_paths.h"
#include "framework/core/error.h"
#include "framework/plugin/plugin_api.h"
#include "framework/report/provenance.h"
#include "framework/scene/scene_cache.h"

#include <dlfcn.h>
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

class Registrar final : public PluginRegistrar {
public:
    void addAccelerator(PluginAccelerator accelerator) override { accelerators.push_back(std::move(accelerator)); }
    void addBuilder(PluginBuilder builder) override { builders.push_back(std::move(builder)); }
    std::vector<PluginAccelerator> accelerators;
    std::vector<PluginBuilder> builders;
};

// The accelerators a builder adds.
std::vector<std::string> acceleratorsOf(const PluginBuilder& builder) {
    return {builder.name, builder.name + "4", builder.name + "8"};
}

// What a plugin adds, checked before any of it is registered.
void checkAdditions(const std::string& plugin, const Registrar& added) {
    if (added.accelerators.empty() && added.builders.empty())
        throw InputError(fmt::format("{}: the plugin adds no accelerator and no builder", plugin));
    std::vector<std::string> names, keyNames;
    auto checkName = [&](const std::string& name) {
        if (name.empty() || name.find_first_of(" \t,:=/") != std::string::npos)
            throw InputError(fmt::format("{}: accelerator name '{}' must be one word without , : = or /", plugin, name));
        if (const AcceleratorInfo* taken = findAccelerator(name); taken || std::count(names.begin(), names.end(), name))
            throw InputError(fmt::format("{}: accelerator '{}' is already defined by {}", plugin, name,
                                         taken && !taken->plugin.empty() ? taken->plugin
                                         : taken                         ? "bvhlab"
                                                                         : "this plugin"));
        names.push_back(name);
    };
    auto checkKeys = [&](const std::string& name, const std::vector<EnvKey>& keys) {
        for (const EnvKey& key : keys) {
            if (key.name.find("::") == std::string::npos)
                throw InputError(fmt::format("{}: env key '{}' of '{}' is not 'Section::key'", plugin, key.name, name));
            if (programKeys().find(key.name) || std::count(keyNames.begin(), keyNames.end(), key.name))
                throw InputError(fmt::format("{}: env key '{}' of '{}' is already declared", plugin, key.name, name));
            keyNames.push_back(key.name);
        }
    };
    for (const PluginAccelerator& a : added.accelerators) {
        checkName(a.name);
        if (!a.create) throw InputError(fmt::format("{}: accelerator '{}' has no factory", plugin, a.name));
        checkKeys(a.name, a.keys);
    }
    for (const PluginBuilder& b : added.builders) {
        for (const std::string& name : acceleratorsOf(b)) checkName(name);
        if (bool(b.splitRule) == bool(b.mergeTree))
            throw InputError(fmt::format("{}: builder '{}' must give exactly one of splitRule and mergeTree", plugin, b.name));
        checkKeys(b.name, b.keys);
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
    using BuildInfoFunction = const PluginBuildInfo* (*)();
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
    // Asked only of a plugin of this version, which has it when its entry points come from BVHLAB_PLUGIN.
    const auto buildInfo = reinterpret_cast<BuildInfoFunction>(dlsym(library, "bvhlab_plugin_build_info"));
    if (!buildInfo)
        throw refuse("it does not export bvhlab_plugin_build_info (define the entry points with BVHLAB_PLUGIN, "
                     "docs/plugins.md)");
    Registrar registrar;
    try {
        registerPlugin(registrar);
    } catch (const std::exception& e) {
        throw refuse(fmt::format("its entry point threw: {}", e.what()));
    } catch (...) {
        throw refuse("its entry point threw an exception that is not a std::exception");
    }
    checkAdditions(name, registrar);

    const SceneCacheKey checksum = sceneCacheKey(file);
    const PluginBuildInfo& build = *buildInfo();
    LoadedPlugin plugin{file, checksum.size, checksum.crc32, apiVersion, {}, build.compiler, build.cxxFlags, build.optimized};
    std::vector<EnvKey> keys;
    for (PluginAccelerator& a : registrar.accelerators) {
        std::vector<std::string> keyNames;
        for (const EnvKey& key : a.keys) {
            keyNames.push_back(key.name);
            keys.push_back(key);
        }
        plugin.accelerators.push_back(a.name);
        addAccelerator({a.name, std::move(a.description), std::move(keyNames), std::move(a.create), name});
    }
    for (const PluginBuilder& b : registrar.builders) {
        keys.insert(keys.end(), b.keys.begin(), b.keys.end());
        for (const std::string& accelerator : acceleratorsOf(b)) plugin.accelerators.push_back(accelerator);
        addBvhBuilder(b, name);
    }
    registerPluginKeys(name, keys);
    recordLoadedPlugin({{"path", name},
                                 {"size", plugin.size},
                                 {"crc32", fmt::format("{:08x}", plugin.crc32)},
                                 {"api_version", plugin.apiVersion},
                                 {"accelerators", plugin.accelerators},
                                 {"compiler", plugin.compiler},
                                 {"cxx_flags", plugin.cxxFlags},
                                 {"optimized", plugin.optimized}});
    if (!plugin.optimized)
        fmt::print(stderr,
                   "warning: plugin {} was compiled without optimisation (flags: {}): its times are not "
                   "representative; rebuild it with -DCMAKE_BUILD_TYPE=Release (docs/plugins.md)\n",
                   name, plugin.cxxFlags.empty() ? "not recorded" : plugin.cxxFlags);
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
                return fmt::format("unknown accelerator '{}': the plugin {} was loaded for it, but it adds {}, not '{}'",
                                   accelerator, plugin.file.string(), fmt::join(plugin.accelerators, ", "),
                                   accelerator);
    return fmt::format("unknown accelerator '{}': none of bvhlab's, no plugin loaded adds it, and no {} in the plugin "
                       "folders ({}). Known: {}",
                       accelerator, fmt::join(pluginFilesFor(accelerator), " or "), pluginFolderList(),
                       fmt::join(known, ", "));
}

void checkKeyIsNotAnUnloadedPlugins(const std::string& key, const std::string& origin) {
    const size_t colons = key.find("::");
    if (programKeys().find(key) || colons == std::string::npos) return;  // a key without a section: Env says so
    const std::string section = key.substr(0, colons + 2);
    for (const auto& [name, declared] : programKeys().keys())
        if (name.starts_with(section)) return;  // a misspelt key of a known section: Env says "did you mean"
    throw InputError(fmt::format("{}: unknown key '{}': no section {} in bvhlab or a loaded plugin. If it is a "
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
            const std::filesystem::path path = folder / file;
            std::error_code ec;
            if (!std::filesystem::is_regular_file(path, ec)) continue;
            loadPlugin(path);
            return findAccelerator(accelerator) != nullptr;
        }
    return false;
}

}  // namespace bvhlab
