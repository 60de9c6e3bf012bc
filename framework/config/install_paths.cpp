#include "framework/config/install_paths.h"

#include "framework/core/error.h"

#include <fmt/format.h>

#include <dlfcn.h>

#include <cstdlib>

namespace bvhlab {
namespace {

// The folder of the shared library this function is compiled into (libbvhlab_config.so): PREFIX/lib
// when installed, a folder of the build tree otherwise.
std::filesystem::path libraryFolder() {
    Dl_info info{};
    if (!dladdr(reinterpret_cast<const void*>(&libraryFolder), &info) || !info.dli_fname) return {};
    std::error_code ec;
    const std::filesystem::path library = std::filesystem::canonical(info.dli_fname, ec);
    return ec ? std::filesystem::path() : library.parent_path();
}

std::filesystem::path installedDataFolderCandidate() {
    return (libraryFolder() / BVHLAB_DATA_FROM_LIBDIR).lexically_normal();
}

bool holdsDefaults(const std::filesystem::path& folder) {
    std::error_code ec;
    return std::filesystem::is_regular_file(folder / "env" / "global.env", ec);
}

// PREFIX/share/bvhlab when this library is installed beside it, else the source tree.
std::filesystem::path findDataFolder() {
    if (const std::filesystem::path installed = installedDataFolderCandidate(); holdsDefaults(installed))
        return installed;
    if (holdsDefaults(BVHLAB_SOURCE_DIR)) return BVHLAB_SOURCE_DIR;
    throw InputError(
        fmt::format("bvhlab's default env files are missing: no env/global.env in {} (where an installed "
                    "bvhlab keeps them) nor in {} (the source tree this bvhlab was built from)",
                    installedDataFolderCandidate().string(), BVHLAB_SOURCE_DIR));
}

}  // namespace

std::filesystem::path dataFolder() {
    static const std::filesystem::path found = findDataFolder();
    return found;
}

std::filesystem::path dataFile(const std::filesystem::path& relative) { return dataFolder() / relative; }

std::filesystem::path bundledPluginFolder() {
    return holdsDefaults(installedDataFolderCandidate()) ? libraryFolder() / "bvhlab" / "plugins"
                                                         : std::filesystem::path(BVHLAB_BINARY_DIR) / "plugins";
}

std::filesystem::path userCacheRoot() {
    if (const char* cache = std::getenv("XDG_CACHE_HOME"); cache && *cache == '/') return cache;
    if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache";
    return std::filesystem::temp_directory_path();
}

}  // namespace bvhlab
