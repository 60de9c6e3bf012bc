// The files and folders a run writes to, checked alike whoever names them.
#pragma once

#include <filesystem>
#include <string>

namespace bvhlab {

// An output path given to `option`: not empty, not a folder (for a file, or a path without
// extension); its folder is created. Throws InputError.
std::filesystem::path prepareOutputFile(const std::string& path, const std::string& option = "--out");
// An output folder given to `option`: not empty; created.
std::filesystem::path prepareOutputFolder(const std::string& path, const std::string& option = "--out");

}  // namespace bvhlab
