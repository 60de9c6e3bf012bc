// Resuming a bench: its JSON records, per scene, the result key of the scene's rows
// (apps/runtime/result_key.h: the program, every structure with its own settings and plugin,
// the scene's content and settings, and the rounds, passes, thread counts and kinds of query).
// A rerun into the same --out keeps a scene's rows as a whole when its key is this run's and
// measures the other scenes: its ratios to Embree hold only between contenders measured in the
// same rounds, so a scene is never made of rows from two runs.
#pragma once

#include "apps/runtime/accel_config.h"
#include "apps/runtime/result_key.h"
#include "framework/config/env.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace bvhlab {

// {"program", "structures": {LABEL: structureKey}, "scene", "measurement"} of one scene's rows.
nlohmann::json benchSceneKey(const std::vector<AccelConfig>& configs, const Env& sceneEnv,
                             const nlohmann::json& measurement);

// The results an earlier bench wrote to `file`: none when it is missing or not a bench's.
class EarlierBench {
public:
    explicit EarlierBench(const std::filesystem::path& file);
    // Whether the rows of the scene `id` can be kept for `key`, and if not, why.
    StoredResult check(const std::string& id, const nlohmann::json& key) const;
    // The scene's record ({"id", "name", "result_key"}) and its rows (those of its "scene_id").
    const nlohmann::json& scene(const std::string& id) const;
    std::vector<nlohmann::json> rows(const std::string& id) const;

private:
    nlohmann::json results_ = nlohmann::json::object();
};

}  // namespace bvhlab
