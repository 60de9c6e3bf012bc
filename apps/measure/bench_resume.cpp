#include "apps/measure/bench_resume.h"

#include <fstream>

namespace bvhlab {

using nlohmann::json;

json benchSceneKey(const std::vector<AccelConfig>& configs, const Env& sceneEnv, const json& measurement) {
    json structures = json::object();
    for (const AccelConfig& config : configs)
        structures[config.label] = structureKey(config.name, accelConfigEnv(config, sceneEnv));
    return {{"program", programIdentity()},
            {"structures", structures},
            {"scene", sceneKey(sceneEnv)},
            {"measurement", measurement}};
}

EarlierBench::EarlierBench(const std::filesystem::path& file) {
    if (!std::filesystem::exists(file)) return;
    try {
        std::ifstream in(file);
        const json results = json::parse(in);
        if (results.at("scenes").is_array() && results.at("rows").is_array()) results_ = results;
    } catch (const std::exception&) {
        // not a bench's results with their keys: nothing to keep
    }
}

const json& EarlierBench::scene(const std::string& id) const {
    static const json none;
    if (!results_.contains("scenes")) return none;
    for (const json& scene : results_["scenes"])
        if (scene.value("id", std::string()) == id) return scene;
    return none;
}

StoredResult EarlierBench::check(const std::string& id, const json& key) const {
    if (scene(id).is_null()) return {false, "new"};
    if (!scene(id).contains("result_key")) return {false, "no result key in the earlier result (an older bvhlab's)"};
    return checkStoredKey(scene(id).at("result_key"), key);
}

std::vector<json> EarlierBench::rows(const std::string& id) const {
    std::vector<json> rows;
    const json& record = scene(id);
    if (record.is_null()) return rows;
    for (const json& row : results_.at("rows"))
        if (row.value("scene_id", std::string()) == id) rows.push_back(row);
    return rows;
}

}  // namespace bvhlab
