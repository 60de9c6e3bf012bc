#pragma once
#include <nlohmann/json.hpp>
#include <string>
namespace bvhlab {
std::string animateSummaryTable(const nlohmann::json& results);
std::string animateFramesCsv(const nlohmann::json& results);
}  // namespace bvhlab
