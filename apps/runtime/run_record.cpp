#include "apps/runtime/run_record.h"

#include "apps/runtime/child_job.h"
#include "apps/runtime/shell_word.h"
#include "framework/scene/scene_cache.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <vector>

namespace bvhlab {
namespace {

std::string commandLine;
std::string started;
std::vector<std::string> warnings;
// This process runs one job of its parent's command (child_job.h): the parent read the same
// arguments first and has said their warnings.
bool childJob = false;

}  // namespace

void recordRun(int argc, char** argv) {
    commandLine.clear();
    for (int i = 0; i < argc; ++i) {
        if (std::string_view(argv[i]) == kChildJobOption) childJob = true;
        if (i > 0) commandLine += ' ';
        commandLine += shellWord(argv[i]);
    }
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    started = text;
}

void warnOfRun(const std::string& warning) {
    if (!childJob) fmt::print(stderr, "warning: {}\n", warning);
    if (std::find(warnings.begin(), warnings.end(), warning) == warnings.end()) warnings.push_back(warning);
}

nlohmann::json runJson() { return {{"command_line", commandLine}, {"started", started}, {"warnings", warnings}}; }

nlohmann::json sceneFileJson(const Scene& scene) {
    if (scene.source.empty()) return {{"file", nullptr}, {"embedded", true}};
    const SceneCacheKey key = sceneCacheKey(scene.source);
    return {{"file", std::filesystem::absolute(scene.source).lexically_normal().string()},
            {"size", key.size},
            {"crc32", fmt::format("{:08x}", key.crc32)},
            {"adler32", fmt::format("{:08x}", key.adler32)}};
}

}  // namespace bvhlab
