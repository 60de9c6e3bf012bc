#include "apps/common/plugins.h"

#include "accel/registry.h"
#include "apps/common/program_keys.h"
#include "framework/config/install_paths.h"
#include "framework/config/plugin_settings.h"
#include "framework/core/error.h"
#include "framework/report/provenance.h"
#include "framework/scene/scene_cache.h"

#include <bvhlab/plugin.h>

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

// What a plugin adds, copied as the registrar is given it (its views may point to temporaries).
struct AddedAccelerator {
    std::string name, description;
    std::vector<EnvKey> keys;
    Accelerator* (*create)(const PluginSettings&) = nullptr;
};
struct AddedBuilder {
    LoadedBuilder builder;
    std::string description;
    std::vector<EnvKey> keys;
};

std::string textOf(const char* text) { return text ? text : ""; }

// The declarations of keys, checked (declarationOf throws, naming what is wrong, out of the
// plugin's entry point: the loader reports it naming the file).
std::vector<EnvKey> declarationsOf(View<const PluginKey> keys) {
    std::vector<EnvKey> declared;
    for (const PluginKey& key : keys) declared.push_back(declarationOf(key));
    return declared;
}

std::vector<std::string> namesOf(const std::vector<EnvKey>& keys) {
    std::vector<std::string> names;
    for (const EnvKey& key : keys) names.push_back(key.name);
    return names;
}

class Registrar final : public PluginRegistrar {
public:
    void addAccelerator(const PluginAccelerator& a) override {
        accelerators.push_back({textOf(a.name), textOf(a.description), declarationsOf(a.keys), a.create});
    }
    void addBuilder(const PluginBuilder& b) override {
        std::vector<EnvKey> keys = declarationsOf(b.keys);
        builders.push_back({{textOf(b.name), namesOf(keys), b.splitRule, b.mergeTree}, textOf(b.description), keys});
    }
    std::vector<AddedAccelerator> accelerators;
    std::vector<AddedBuilder> builders;
};

// A hash of an ABI's figures, to name it in a line: 16 hex digits.
std::string abiFingerprint(View<const AbiFigure> figures) {
    uint64_t h = abi::hash("");
    for (const AbiFigure& f : figures) h = abi::hash(fmt::format("{}={};", f.what, f.value).c_str(), h);
    return fmt::format("{:016x}", h);
}

// Why a plugin whose ABI is `plugin` cannot be loaded into this bvhlab, or "" when it can: both
// fingerprints and the figures in which they differ.
std::string abiMismatch(View<const AbiFigure> plugin) {
    const View<const AbiFigure> own = kAbi;
    std::vector<std::string> differences;
    auto valueIn = [](View<const AbiFigure> figures, std::string_view what) -> std::optional<uint64_t> {
        for (const AbiFigure& f : figures)
            if (what == f.what) return f.value;
        return std::nullopt;
    };
    auto shown = [](std::optional<uint64_t> v) { return v ? fmt::format("{}", *v) : std::string("none"); };
    for (const AbiFigure& f : own)
        if (const std::optional<uint64_t> theirs = valueIn(plugin, f.what); theirs != f.value)
            differences.push_back(fmt::format("{}: plugin {}, bvhlab {}", f.what, shown(theirs), f.value));
    for (const AbiFigure& f : plugin)
        if (!valueIn(own, f.what)) differences.push_back(fmt::format("{}: plugin {}, bvhlab none", f.what, f.value));
    if (differences.empty()) return "";
    constexpr size_t kShown = 8;
    const size_t more = differences.size() > kShown ? differences.size() - kShown : 0;
    differences.resize(differences.size() - more);
    return fmt::format("built against another ABI: plugin ABI {}, bvhlab ABI {}; they differ in {}{}. Rebuild the "
                       "plugin against this bvhlab's headers (docs/plugins.md)",
                       abiFingerprint(plugin), abiFingerprint(own), fmt::join(differences, "; "),
                       more ? fmt::format(" and {} more", more) : "");
}

// The accelerators a builder adds.
std::vector<std::string> acceleratorsOf(const AddedBuilder& added) {
    const std::string& name = added.builder.name;
    return {name, name + "4", name + "8"};
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
    for (const AddedAccelerator& a : added.accelerators) {
        checkName(a.name);
        if (!a.create) throw InputError(fmt::format("{}: accelerator '{}' has no factory", plugin, a.name));
        checkKeys(a.name, a.keys);
    }
    for (const AddedBuilder& b : added.builders) {
        for (const std::string& name : acceleratorsOf(b)) checkName(name);
        if (bool(b.builder.splitRule) == bool(b.builder.mergeTree))
            throw InputError(fmt::format("{}: builder '{}' must give exactly one of splitRule and mergeTree", plugin,
                                         b.builder.name));
        checkKeys(b.builder.name, b.keys);
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
    using AbiFunction = const AbiFigure* (*)(size_t*);
    using BuildInfoFunction = const PluginBuildInfo* (*)();
    using RegisterFunction = void (*)(PluginRegistrar&);
    const auto abiOf = reinterpret_cast<AbiFunction>(dlsym(library, "bvhlab_plugin_abi"));
    const auto buildInfo = reinterpret_cast<BuildInfoFunction>(dlsym(library, "bvhlab_plugin_build_info"));
    const auto registerPlugin = reinterpret_cast<RegisterFunction>(dlsym(library, "bvhlab_register_plugin"));
    if (!abiOf && dlsym(library, "bvhlab_plugin_api_version"))
        throw refuse("built for an older bvhlab, whose plugins carry an API version instead of an ABI: rebuild it "
                     "against this bvhlab's headers (docs/plugins.md)");
    if (!abiOf || !buildInfo || !registerPlugin)
        throw refuse("not a bvhlab plugin: it does not export bvhlab_plugin_abi, bvhlab_plugin_build_info and "
                     "bvhlab_register_plugin (define them with BVHLAB_PLUGIN, docs/plugins.md)");
    size_t abiSize = 0;
    const AbiFigure* abiFigures = abiOf(&abiSize);
    constexpr size_t kMostFigures = 4096;  // bvhlab's are a hundred: more is not an ABI
    if (!abiFigures || abiSize > kMostFigures ||
        std::any_of(abiFigures, abiFigures + abiSize, [](const AbiFigure& f) { return !f.what; }))
        throw refuse("its ABI is unreadable: rebuild it against this bvhlab's headers (docs/plugins.md)");
    const View<const AbiFigure> abi(abiFigures, abiSize);
    if (const std::string mismatch = abiMismatch(abi); !mismatch.empty()) throw refuse(mismatch);
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
    LoadedPlugin plugin{file,           checksum.size,        checksum.crc32,    abiFingerprint(abi), {},
                        textOf(build.compiler), textOf(build.cxxFlags), build.optimized};
    std::vector<EnvKey> keys;
    for (AddedAccelerator& a : registrar.accelerators) {
        keys.insert(keys.end(), a.keys.begin(), a.keys.end());
        plugin.accelerators.push_back(a.name);
        auto create = [create = a.create, keyNames = namesOf(a.keys), name = a.name](const Env& env) {
            const EnvPluginSettings settings(env, keyNames, fmt::format("accelerator '{}'", name));
            return std::unique_ptr<Accelerator>(create(settings));
        };
        addAccelerator({a.name, std::move(a.description), namesOf(a.keys), std::move(create), name});
    }
    for (const AddedBuilder& b : registrar.builders) {
        keys.insert(keys.end(), b.keys.begin(), b.keys.end());
        for (const std::string& accelerator : acceleratorsOf(b)) plugin.accelerators.push_back(accelerator);
        addBvhBuilder(b.builder, b.description, name);
    }
    registerPluginKeys(name, keys);
    recordLoadedPlugin({{"path", name},
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
