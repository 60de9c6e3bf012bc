#include "apps/batch/batch_resume.h"

#include "apps/runtime/app_keys.h"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <fstream>

namespace bvhlab {

using nlohmann::json;

StoredResult checkFinishedJob(const std::filesystem::path& out, const std::string& name, const json& key,
                              const Env& env) {
    const std::filesystem::path file = out / "jobs" / (name + ".json");
    StoredResult stored = checkStoredResult(file, key);
    if (!stored.keep) return stored;
    std::ifstream in(file);
    const json job = json::parse(in);
    if (job.value("animated", false)) return stored;  // an animation's job writes no images
    for (const char* run : {"no_shadows", "shadows"}) {
        const json& record = job.at("runs").at(run);
        const json images = record.value("images", json::object());
        if (!images.contains("png") || (env.get(keys::Output::exr) && !images.contains("exr")))
            return {false, "its images were not all written (Output::exr)"};
        if (env.get(keys::Output::heatmap) && !record.contains("heatmap"))
            return {false, "its heat maps were not drawn (the run stopped before its scene's last job)"};
        for (const auto& [kind, image] : images.items())
            if (!std::filesystem::exists(out / image.get<std::string>())) return {false, "an image of it is missing"};
    }
    return stored;
}

std::optional<HeatmapScale> keptHeatmapScale(const std::vector<json>& keptJobs) {
    std::vector<std::string> accels;
    std::optional<float> steps;
    for (const json& job : keptJobs)
        for (const char* run : {"no_shadows", "shadows"}) {
            if (!job.contains("runs")) continue;  // an animation's job
            const json record = job.at("runs").at(run).value("heatmap", json::object());
            if (!record.contains("scale")) continue;
            steps = record.at("scale").get<float>();
            const std::string accel = job.at("accel").get<std::string>();
            if (accels.empty() || accels.back() != accel) accels.push_back(accel);
        }
    if (!steps) return std::nullopt;
    return HeatmapScale{*steps,
                        fmt::format("that of the scene's jobs kept from an earlier run: {}", fmt::join(accels, ", "))};
}

}  // namespace bvhlab
