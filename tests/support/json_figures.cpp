#include "tests/support/json_figures.h"

#include <functional>

namespace bvhlab::test {

std::vector<nlohmann::json> figuresWith(const nlohmann::json& json, const char* name) {
    std::vector<nlohmann::json> found;
    std::function<void(const nlohmann::json&)> walk = [&](const nlohmann::json& j) {
        if (j.is_object()) {
            if (j.contains("figures") && j["figures"].contains(name)) found.push_back(j["figures"]);
            for (const auto& [key, value] : j.items()) walk(value);
        } else if (j.is_array()) {
            for (const auto& value : j) walk(value);
        }
    };
    walk(json);
    return found;
}

}  // namespace bvhlab::test
