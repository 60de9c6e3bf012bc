#include "accel/plugins/plugin_loader.h"

#include "framework/config/plugin_settings.h"
#include "framework/core/error.h"

#include <dlfcn.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <optional>

namespace bvhlab {
namespace {

std::string textOf(const char* text) { return text ? text : ""; }

// The declarations of keys, checked (declarationOf throws, naming what is wrong, out of the
// plugin's entry point: openPlugin reports it naming the file).
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

// What the entry point adds, copied as it is given (its views may point to temporaries).
class Registrar final : public PluginRegistrar {
public:
    void addAccelerator(const PluginAccelerator& a) override {
        accelerators.push_back({textOf(a.name), textOf(a.description), declarationsOf(a.keys), a.create});
    }
    void addBuilder(const PluginBuilder& b) override {
        std::vector<EnvKey> keys = declarationsOf(b.keys);
        builders.push_back({{textOf(b.name), namesOf(keys), b.splitRule, b.mergeTree}, textOf(b.description), keys});
    }
    std::vector<PluginAcceleratorEntry> accelerators;
    std::vector<PluginBuilderEntry> builders;
};

// What a plugin adds, checked in itself before any of it is registered.
void checkAdditions(const std::string& file, const OpenedPlugin& plugin) {
    if (plugin.accelerators.empty() && plugin.builders.empty())
        throw inputError(file, 0, "the plugin adds no accelerator and no builder");
    std::vector<std::string> names;
    for (const std::string& name : plugin.acceleratorNames()) {
        if (name.empty() || name.find_first_of(" \t,:=/") != std::string::npos)
            throw inputError(file, 0, fmt::format("accelerator name '{}' must be one word without , : = or /", name));
        if (std::count(names.begin(), names.end(), name))
            throw inputError(file, 0, fmt::format("accelerator '{}' is already defined by this plugin", name));
        names.push_back(name);
    }
    std::vector<std::string> keyNames;
    for (const EnvKey& key : plugin.keys()) {
        if (std::count(keyNames.begin(), keyNames.end(), key.name))
            throw inputError(file, 0, fmt::format("env key '{}' is declared twice", key.name));
        keyNames.push_back(key.name);
    }
    for (const PluginAcceleratorEntry& a : plugin.accelerators)
        if (!a.create) throw inputError(file, 0, fmt::format("accelerator '{}' has no factory", a.name));
    for (const PluginBuilderEntry& b : plugin.builders)
        if (bool(b.builder.splitRule) == bool(b.builder.mergeTree))
            throw inputError(
                file, 0, fmt::format("builder '{}' must give exactly one of splitRule and mergeTree", b.builder.name));
}

}  // namespace

void CloseLibrary::operator()(void* library) const { dlclose(library); }

std::vector<std::string> PluginBuilderEntry::acceleratorNames() const {
    return {builder.name, builder.name + "4", builder.name + "8"};
}

std::vector<std::string> OpenedPlugin::acceleratorNames() const {
    std::vector<std::string> names;
    for (const PluginAcceleratorEntry& a : accelerators) names.push_back(a.name);
    for (const PluginBuilderEntry& b : builders)
        for (std::string& name : b.acceleratorNames()) names.push_back(std::move(name));
    return names;
}

std::vector<EnvKey> OpenedPlugin::keys() const {
    std::vector<EnvKey> keys;
    for (const PluginAcceleratorEntry& a : accelerators) keys.insert(keys.end(), a.keys.begin(), a.keys.end());
    for (const PluginBuilderEntry& b : builders) keys.insert(keys.end(), b.keys.begin(), b.keys.end());
    return keys;
}

std::string abiFingerprint(View<const AbiFigure> figures) {
    uint64_t h = abi::hash("");
    for (const AbiFigure& f : figures) h = abi::hash(fmt::format("{}={};", f.what, f.value).c_str(), h);
    return fmt::format("{:016x}", h);
}

std::string abiMismatch(View<const AbiFigure> plugin) {
    const View<const AbiFigure> own = abiFigures();
    auto valueIn = [](View<const AbiFigure> figures, std::string_view what) -> std::optional<uint64_t> {
        for (const AbiFigure& f : figures)
            if (what == f.what) return f.value;
        return std::nullopt;
    };
    // The figures of the toolchain, each with its own cause; every other figure, and a toolchain
    // figure the plugin lacks (its headers are older than that figure), comes from the headers.
    const std::vector<std::string_view> toolchain = {"Itanium C++ ABI", "standard library", "standard library ABI"};
    const std::optional<uint64_t> itanium = valueIn(plugin, toolchain[0]);
    const std::optional<uint64_t> library = valueIn(plugin, toolchain[1]);
    const std::optional<uint64_t> libraryAbi = valueIn(plugin, toolchain[2]);
    auto libraryName = [](uint64_t library) {
        return library == abi::kLibstdcxx ? "libstdc++"
               : library == abi::kLibcxx  ? "libc++"
                                          : "another standard library";
    };
    std::vector<std::string> causes;
    if (itanium && *itanium != abi::kItaniumAbi)
        causes.push_back(
            "it was not compiled for the Itanium C++ ABI, which bvhlab follows: build it with GCC or Clang");
    if (library && *library != abi::kStandardLibrary)
        causes.push_back(fmt::format("it was built with {}; bvhlab uses {}: build it with {}{}", libraryName(*library),
                                     libraryName(abi::kStandardLibrary), libraryName(abi::kStandardLibrary),
                                     *library == abi::kLibcxx ? " (without -stdlib=libc++)" : ""));
    else if (libraryAbi && *libraryAbi != abi::kStandardLibraryAbi)
        causes.push_back(abi::kStandardLibrary == abi::kLibstdcxx
                             ? fmt::format("it was built with _GLIBCXX_USE_CXX11_ABI={}, bvhlab with {}: build it with "
                                           "-D_GLIBCXX_USE_CXX11_ABI={}",
                                           *libraryAbi, abi::kStandardLibraryAbi, abi::kStandardLibraryAbi)
                             : fmt::format("it was built for the ABI version {} of {}, bvhlab for {}: build it for {}",
                                           *libraryAbi, libraryName(abi::kStandardLibrary), abi::kStandardLibraryAbi,
                                           abi::kStandardLibraryAbi));

    // A type's figure is a hash: that it differs is all there is to say of it.
    std::vector<std::string> differences;
    auto differ = [&](std::string_view what, std::optional<uint64_t> theirs, std::optional<uint64_t> ours) {
        if (!theirs || !ours)
            differences.push_back(fmt::format("{} is absent in {}", what, theirs ? "bvhlab" : "the plugin"));
        else if (what.starts_with("type of "))
            differences.push_back(fmt::format("the {} differs", what));
        else if (!std::count(toolchain.begin(), toolchain.end(), what))
            differences.push_back(fmt::format("{} is {} in the plugin, {} in bvhlab", what, *theirs, *ours));
    };
    for (const AbiFigure& f : own)
        if (const std::optional<uint64_t> theirs = valueIn(plugin, f.what); theirs != f.value)
            differ(f.what, theirs, f.value);
    for (const AbiFigure& f : plugin)
        if (!valueIn(own, f.what)) differ(f.what, f.value, std::nullopt);
    if (!differences.empty()) {
        constexpr size_t kShown = 8;
        const size_t more = differences.size() > kShown ? differences.size() - kShown : 0;
        differences.resize(differences.size() - more);
        causes.push_back(
            fmt::format("it was built against other headers ({}{}): rebuild it against this bvhlab's "
                        "include/bvhlab (docs/plugins.md)",
                        fmt::join(differences, "; "), more ? fmt::format("; and {} more", more) : ""));
    }
    if (causes.empty()) return "";
    return fmt::format("built against another ABI (plugin ABI {}, bvhlab ABI {}): {}", abiFingerprint(plugin),
                       abiFingerprint(own), fmt::join(causes, "; "));
}

OpenedPlugin openPlugin(const std::filesystem::path& file) {
    const std::string name = file.string();
    OpenedPlugin plugin;
    plugin.file = file;
    plugin.library.reset(dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL));
    if (!plugin.library) throw inputError(file, 0, fmt::format("cannot load as a plugin: {}", dlerror()));
    void* library = plugin.library.get();

    using AbiFunction = const AbiFigure* (*)(size_t*);
    using BuildInfoFunction = const PluginBuildInfo* (*)();
    using RegisterFunction = void (*)(PluginRegistrar&);
    const auto abiOf = reinterpret_cast<AbiFunction>(dlsym(library, "bvhlab_plugin_abi"));
    const auto buildInfo = reinterpret_cast<BuildInfoFunction>(dlsym(library, "bvhlab_plugin_build_info"));
    const auto registerPlugin = reinterpret_cast<RegisterFunction>(dlsym(library, "bvhlab_register_plugin"));
    if (!abiOf && dlsym(library, "bvhlab_plugin_api_version"))
        throw inputError(file, 0,
                         "built for an older bvhlab, whose plugins carry an API version instead of an ABI: rebuild "
                         "it against this bvhlab's headers (docs/plugins.md)");
    if (!abiOf || !buildInfo || !registerPlugin)
        throw inputError(file, 0,
                         "not a bvhlab plugin: it does not export bvhlab_plugin_abi, bvhlab_plugin_build_info and "
                         "bvhlab_register_plugin (define them with BVHLAB_PLUGIN, docs/plugins.md)");
    size_t abiSize = 0;
    const AbiFigure* abiFigures = abiOf(&abiSize);
    constexpr size_t kMostFigures = 4096;  // bvhlab's are a hundred: more is not an ABI
    if (!abiFigures || abiSize > kMostFigures ||
        std::any_of(abiFigures, abiFigures + abiSize, [](const AbiFigure& f) { return !f.what; }))
        throw inputError(file, 0, "its ABI is unreadable: rebuild it against this bvhlab's headers (docs/plugins.md)");
    const View<const AbiFigure> abi(abiFigures, abiSize);
    if (const std::string mismatch = abiMismatch(abi); !mismatch.empty()) throw inputError(file, 0, mismatch);
    plugin.abi = abiFingerprint(abi);

    const PluginBuildInfo& build = *buildInfo();
    plugin.compiler = textOf(build.compiler);
    plugin.cxxFlags = textOf(build.cxxFlags);
    plugin.optimized = build.optimized;

    Registrar registrar;
    try {
        registerPlugin(registrar);
    } catch (const std::exception& e) {
        throw inputError(file, 0, fmt::format("its entry point threw: {}", e.what()));
    } catch (...) {
        throw inputError(file, 0, "its entry point threw an exception that is not a std::exception");
    }
    plugin.accelerators = std::move(registrar.accelerators);
    plugin.builders = std::move(registrar.builders);
    checkAdditions(name, plugin);
    return plugin;
}

}  // namespace bvhlab
