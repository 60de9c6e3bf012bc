// Where a number came from: the code, the compiler and the machine.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace bvhlab {

std::string gitCommit();
std::string cpuModel();  // from /proc/cpuinfo, "unknown" elsewhere
// {"git_commit", "compiler", "cxx_flags", "cpu", "hardware_threads"}
nlohmann::json provenanceJson();

}  // namespace bvhlab
