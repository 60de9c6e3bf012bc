// Where bvhlab finds what it ships beside its program: the default env files (env/global.env,
// env/scenes/*.env, env/scenes.list) and its own plugins. Found from the location of this
// library, so an installed prefix works wherever it is moved, with the source tree gone; a build
// tree reads the source tree it was built from. Never from the current directory.
#pragma once

#include <filesystem>

namespace bvhlab {

// The folder holding env/: PREFIX/share/bvhlab when installed, the repository root in a build
// tree. Throws InputError naming where it looked when neither holds env/global.env.
std::filesystem::path dataFolder();

// dataFolder() / relative, e.g. dataFile("env/global.env").
std::filesystem::path dataFile(const std::filesystem::path& relative);

// The plugins bvhlab ships (the grid): PREFIX/lib/bvhlab/plugins, or build/plugins.
std::filesystem::path bundledPluginFolder();

// The user's cache folder: $XDG_CACHE_HOME, else ~/.cache (XDG base directories), else the
// system's temporary folder when there is no home. A default path written "$XDG_CACHE_HOME/..."
// resolves against it (Scene::cacheDir).
std::filesystem::path userCacheRoot();

}  // namespace bvhlab
