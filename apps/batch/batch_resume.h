// Resuming a batch: a rerun into a folder of the same batch keeps each finished job and runs the
// rest. A job is finished when its file in DIR/jobs carries the result key it would be run with
// now (apps/runtime/result_key.h: the program, the structure with its plugin, the scene's content
// and settings) and this run's outputs are all there: its PNGs, its EXRs with Output::exr, and its
// heat maps with Output::heatmap (drawn after its scene's last job: the jobs of a scene that was
// interrupted have none, and run again, so that the scene's heat maps share one scale). An
// animated scene's job writes no images: its file is all.
#pragma once

#include "apps/runtime/result_key.h"
#include "framework/config/env.h"
#include "framework/io/heatmap.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace bvhlab {

// Whether the job `name` in `out` is finished for `key` and the outputs `env` asks for, and if not, why.
StoredResult checkFinishedJob(const std::filesystem::path& out, const std::string& name, const nlohmann::json& key,
                              const Env& env);

// The heat map scale of a scene's kept jobs, which the scene's jobs run now are drawn at too;
// nullopt when none of them has a heat map.
std::optional<HeatmapScale> keptHeatmapScale(const std::vector<nlohmann::json>& keptJobs);

}  // namespace bvhlab
