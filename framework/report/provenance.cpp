#include "framework/report/provenance.h"

#include <bvhlab_git_commit.h>  // generated at every build: BVHLAB_GIT_COMMIT

#include <nlohmann/json.hpp>

#include <fstream>
#include <thread>

namespace bvhlab {

std::string gitCommit() { return BVHLAB_GIT_COMMIT; }

std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) {
            const size_t colon = line.find(':');
            if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
        }
    return "unknown";
}

namespace {

nlohmann::json& loadedPlugins() {
    static nlohmann::json plugins = nlohmann::json::array();
    return plugins;
}

}  // namespace

void recordLoadedPlugin(nlohmann::json plugin) { loadedPlugins().push_back(std::move(plugin)); }

nlohmann::json provenanceJson() {
    return {{"git_commit", gitCommit()},
            {"compiler", BVHLAB_COMPILER},
            {"cxx_flags", BVHLAB_CXX_FLAGS},
            {"cpu", cpuModel()},
            {"hardware_threads", std::thread::hardware_concurrency()},
            {"plugins", loadedPlugins()}};
}

}  // namespace bvhlab
