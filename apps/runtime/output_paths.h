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

// A label made a file name of letters, digits and . _ - + only, so that no shell, make or
// Slurm script trips on it: ':' becomes '_' and '=' becomes '-', anything else '_'
// (sahbvh:BVH::bins=4 -> sahbvh_BVH__bins-4). Used wherever an --accel label names a file.
std::string labelAsFileName(const std::string& label);

}  // namespace bvhlab
