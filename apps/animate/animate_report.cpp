#include "apps/animate/animate_report.h"
namespace bvhlab {
std::string animateSummaryTable(const nlohmann::json& results) { return results.dump(1) + "\n"; }
std::string animateFramesCsv(const nlohmann::json&) { return ""; }
}  // namespace bvhlab
