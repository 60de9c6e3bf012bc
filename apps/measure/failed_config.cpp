#include "apps/measure/failed_config.h"

#include "apps/runtime/table_text.h"

#include <fmt/core.h>

#include <algorithm>

namespace bvhlab {

using nlohmann::json;

json failedConfigResult(const std::string& sceneId, const AccelConfig& config, const std::string& reason) {
    return {{"scene", sceneId}, {"config", config.label}, {"accel", config.name}, {"failed", reason}};
}

bool isFailedConfig(const json& stored) { return stored.contains("failed"); }

std::string failedConfigCsvRow(const json& stored, const std::string& header) {
    const size_t separators = size_t(std::count(header.begin(), header.end(), ','));
    std::string row =
        fmt::format("{},{},{}", csvText(stored.at("scene").get<std::string>()),
                    csvText(stored.at("config").get<std::string>()), csvText(stored.at("accel").get<std::string>()));
    row += std::string(separators - 2, ',');  // the columns between accel and failed left empty
    return row + csvText(stored.at("failed").get<std::string>()) + "\n";
}

std::vector<std::string> failedConfigCells(const json& stored, size_t columns, const std::string& filler) {
    std::vector<std::string> cells = {stored.at("scene").get<std::string>(), stored.at("config").get<std::string>(),
                                      "failed: " + markdownText(stored.at("failed").get<std::string>())};
    cells.resize(std::max(columns, cells.size()), filler);
    return cells;
}

std::string failedConfigMarkdownRow(const json& stored, size_t columns) {
    std::string row = "|";
    for (const std::string& cell : failedConfigCells(stored, columns, ""))
        row += cell.empty() ? " |" : " " + cell + " |";
    return row + "\n";
}

}  // namespace bvhlab
