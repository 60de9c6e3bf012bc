#include "accel/plugins/plugin_loader.h"

#include "framework/core/error.h"

#include <dlfcn.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <optional>

namespace bvhlab {
void CloseLibrary::operator()(void* library) const { dlclose(library); }

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
    plugin.compiler = pluginText(build.compiler);
    plugin.cxxFlags = pluginText(build.cxxFlags);
    plugin.optimized = build.optimized;

    RecordingRegistrar registrar;
    try {
        registerPlugin(registrar);
    } catch (const std::exception& e) {
        throw inputError(file, 0, fmt::format("its entry point threw: {}", e.what()));
    } catch (...) {
        throw inputError(file, 0, "its entry point threw an exception that is not a std::exception");
    }
    plugin.additions = std::move(registrar.additions);
    checkAdditions(name, plugin.additions);
    return plugin;
}

}  // namespace bvhlab
