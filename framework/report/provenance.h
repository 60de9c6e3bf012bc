// Where a number came from: the code, the compiler and the machine.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace bvhlab {

std::string gitCommit();
std::string cpuModel();  // from /proc/cpuinfo, "unknown" elsewhere
// {"git_commit", "compiler", "cxx_flags", "cpu", "hardware_threads", "plugins"}
nlohmann::json provenanceJson();
// A plugin loaded by this process ({"path", "size", "crc32", "api_version", "accelerators"}),
// listed under "plugins" in every provenance made after.
void recordLoadedPlugin(nlohmann::json plugin);

}  // namespace bvhlab
