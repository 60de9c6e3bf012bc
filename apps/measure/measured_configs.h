// What a tradeoff folder holds, DIR/<scene>/<config>.json, as the report writers read it: the
// measured configurations as rows of the report's own kind, the failed ones (failed_config.h) as
// stored. A configuration without a file is in neither.
#pragma once

#include "apps/measure/failed_config.h"
#include "apps/runtime/accel_config.h"
#include "apps/runtime/output_paths.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace bvhlab {

template <typename Row>
struct MeasuredConfigs {
    std::map<std::string, std::map<std::string, Row>> rows;                 // scene -> label -> row
    std::map<std::string, std::map<std::string, nlohmann::json>> failures;  // scene -> label -> its failure

    const Row* row(const std::string& scene, const std::string& label) const { return find(rows, scene, label); }
    const nlohmann::json* failure(const std::string& scene, const std::string& label) const {
        return find(failures, scene, label);
    }

private:
    template <typename T>
    static const T* find(const std::map<std::string, std::map<std::string, T>>& byScene, const std::string& scene,
                         const std::string& label) {
        const auto byLabel = byScene.find(scene);
        if (byLabel == byScene.end()) return nullptr;
        const auto found = byLabel->second.find(label);
        return found == byLabel->second.end() ? nullptr : &found->second;
    }
};

// Reads the file of every scene and configuration there is; makeRow(json) makes a measured one's row.
template <typename Row, typename MakeRow>
MeasuredConfigs<Row> readMeasuredConfigs(const std::filesystem::path& dir, const std::vector<std::string>& sceneIds,
                                         const std::vector<AccelConfig>& configs, MakeRow makeRow) {
    MeasuredConfigs<Row> measured;
    for (const std::string& scene : sceneIds)
        for (const AccelConfig& config : configs) {
            const std::filesystem::path file = dir / scene / (labelAsFileName(config.label) + ".json");
            if (!std::filesystem::exists(file)) continue;
            std::ifstream in(file);
            nlohmann::json stored = nlohmann::json::parse(in);
            if (isFailedConfig(stored))
                measured.failures[scene][config.label] = std::move(stored);
            else
                measured.rows[scene][config.label] = makeRow(std::move(stored));
        }
    return measured;
}

}  // namespace bvhlab
