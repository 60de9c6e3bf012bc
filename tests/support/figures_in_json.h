// The structure's own figures wherever a command's JSON holds its statistics row: every "figures"
// object that has the figure `name`, in the order they appear.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace bvhlab::test {

inline void collectFigures(const nlohmann::json& j, const std::string& name, std::vector<nlohmann::json>& found) {
    if (j.is_object()) {
        if (j.contains("figures") && j["figures"].contains(name)) found.push_back(j["figures"]);
        for (const auto& [key, value] : j.items()) collectFigures(value, name, found);
    } else if (j.is_array()) {
        for (const auto& value : j) collectFigures(value, name, found);
    }
}

inline std::vector<nlohmann::json> figuresWith(const nlohmann::json& j, const std::string& name) {
    std::vector<nlohmann::json> found;
    collectFigures(j, name, found);
    return found;
}

}  // namespace bvhlab::test
