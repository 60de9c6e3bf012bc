// A build's statistics as JSON, the one writer of every output that reports a tree: the render's
// statistics row, the Python module's accel.stats, and the records of bench, builders and tradeoff.
#pragma once

#include "framework/core/accelerator.h"

#include <nlohmann/json.hpp>

#include <vector>

namespace bvhlab {

// The names of the two leaf figures. The builders' result files call them avg_leaf and max_leaf,
// and a resumed run reads the files written before, so those keep their names.
struct LeafFigureNames {
    const char* mean = "avg_leaf_prims";
    const char* largest = "max_leaf_prims";
};

// nodes, leaves, avg_leaf_prims, max_leaf_prims, max_depth, bytes, sah, sah_c_trav, sah_c_isect,
// epo, leaf_sizes ([k]: leaves of k primitives) and figures; a figure the structure does not
// report is null. Not the build times, which each caller reports its own way (one build or the
// median of several).
nlohmann::json buildStatsJson(const BuildStats& stats, const LeafFigureNames& leafNames = {});

// A structure's own figures: {"name": {"value", "meaning"}, ...}.
nlohmann::json figuresJson(const std::vector<NamedFigure>& figures);

}  // namespace bvhlab
