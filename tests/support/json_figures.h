// The structure's own figures in a JSON bvhlab wrote, wherever its statistics row sits.
#pragma once

#include <nlohmann/json.hpp>

#include <vector>

namespace bvhlab::test {

// Every "figures" object of `json` that holds a figure named `name`.
std::vector<nlohmann::json> figuresWith(const nlohmann::json& json, const char* name);

}  // namespace bvhlab::test
