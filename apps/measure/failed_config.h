// A configuration of a tradeoff whose job failed (it crashed, threw or ran past --job-timeout,
// apps/runtime/child_job.h). DIR/<scene>/<config>.json then holds the reason alone, without the
// fingerprint, so that the next run measures it again. The report writers show it as a row of its
// own, "failed: REASON", and leave it out of every figure, ratio, Pareto front and correlation.
#pragma once

#include "apps/runtime/accel_config.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace bvhlab {

// What DIR/<scene>/<config>.json holds for a configuration that failed for `reason`.
nlohmann::json failedConfigResult(const std::string& sceneId, const AccelConfig& config, const std::string& reason);

bool isFailedConfig(const nlohmann::json& stored);

// The failed configuration's row of a CSV file under `header` (its first columns scene, config,
// accel, its last one "failed"): those three, empty cells, the reason last.
std::string failedConfigCsvRow(const nlohmann::json& stored, const std::string& header);

// Its cells in a Markdown table of `columns` columns, the first two scene and config: those two,
// "failed: REASON", then `filler` ("n/a" where a table leaves out the columns n/a in every row).
std::vector<std::string> failedConfigCells(const nlohmann::json& stored, size_t columns, const std::string& filler);

// The same as one Markdown row, the other cells empty: "| scene | config | failed: REASON | | |".
std::string failedConfigMarkdownRow(const nlohmann::json& stored, size_t columns);

}  // namespace bvhlab
