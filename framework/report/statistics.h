// The statistics row in the report's terms (#Prims, #Nodes, #Leaves, SAH, T_B, T_R, N_IT,
// N_TR, N_Q, render time), for primary and shadow queries apart, as a table and as JSON.
#pragma once

#include "framework/core/accelerator.h"
#include "framework/render/renderer.h"
#include "framework/scene/scene.h"

#include <nlohmann/json.hpp>

#include <string>

namespace bvhlab {

struct StatsRow {
    std::string scene;
    std::string accel;
    size_t prims = 0;         // primitives in the scene (every kind), degenerate ones included
    LoadReport load;          // what loading skipped: degenerate triangles, spheres, cones
    bool hasCounters = true;  // false: N_IT and N_TR unavailable
    BuildStats build;
    RenderStats render;
};

// The table printed after a render (two lines: primary, shadow).
std::string formatStatsTable(const StatsRow& row);

// JSON with keys scene, accel, prims, degenerate, degenerate_spheres, degenerate_cones,
// skipped_polygons, ear_clipped_polygons, build_ms, render_ms, threads, the tree's statistics
// (buildStatsJson: nodes, leaves, sah, epo, leaf_sizes, figures...) and objects primary/shadow
// {queries, t_r_us and the counters of kQueryCounters: n_it, n_tr, ...}; unavailable values are null.
nlohmann::json statsJson(const StatsRow& row);

}  // namespace bvhlab
