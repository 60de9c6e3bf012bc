// The scenes a batch or bench runs over: env files, one per scene, named directly or through
// .list files (one env file per line, relative to the list's folder, `#` comments).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace bvhlab {

// Expands .list files; with no arguments, env/scenes.list of the repository.
std::vector<std::filesystem::path> expandSceneList(const std::vector<std::string>& arguments);

}  // namespace bvhlab
