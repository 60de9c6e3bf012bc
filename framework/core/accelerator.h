// bvhlab's side of the accelerator interface (<bvhlab/accelerator.h>, the plugin API): the
// statistics of a build as one struct, filled by bvhlab's own structures, by name from a plugin's.
#pragma once

#include <bvhlab/math.h>
#include "framework/core/native_ray_batch.h"

#include <bvhlab/accelerator.h>

#include <optional>
#include <string>
#include <vector>

namespace bvhlab {

// SAH cost normalised by the root box: C_trav * sum over inner nodes of A(n)/A(root)
// + C_isect * sum over leaves of A(l)/A(root) * N(l). The constants are stated with it.
struct SahCost {
    double cost = 0.0;
    double cTraversal = 1.0;
    double cIntersect = 1.0;
};

// A figure of a structure's own, beside the common ones: a grid's resolution and references
// per voxel, a kd-tree's empty leaves.
struct NamedFigure {
    std::string name;  // one word, as the JSON key: "voxels"
    double value = 0.0;
    std::string meaning;  // one line: "N_V, cells of the grid"
};

// What a build reports: its times, measured by the caller around build() (timed_build.h), and
// the structure's statistics. Structures without a visible tree (Embree) leave the tree fields
// unset: unavailable, not zero. Each field is a name of BuildStatistics (<bvhlab/statistics.h>).
struct BuildStats {
    // T_B in wall time, and the process's CPU time over the same call (all threads). Left 0
    // by the statistics: the caller times build(), so every structure is timed alike.
    double buildMs = 0.0;
    double buildCpuMs = 0.0;
    size_t primitives = 0;        // primitives built over (degenerate ones excluded)
    std::optional<size_t> nodes;  // all nodes, leaves included
    std::optional<size_t> leaves;
    std::optional<double> avgLeafPrimitives;
    std::optional<size_t> maxLeafPrimitives;
    std::optional<int> maxDepth;
    // The depth the structure promises to stay below (its traversal stacks hold that many
    // levels), and the most primitives it promises a leaf holds; unset where it promises none.
    // Checked by `bvhlab stress` and the stress tests, which hold a structure to what it
    // promises and every structure to bounded build time and memory; not reported.
    std::optional<int> depthBound;
    std::optional<size_t> leafBound;
    std::optional<SahCost> sah;
    // End-point overlap (Aila, Karras and Laine 2013) with the SAH's constants: the area of
    // geometry inside node boxes but not in their subtrees, by node cost, over all geometry's
    // area. Unset where the tree is invisible or it was not computed (large scenes).
    std::optional<double> epo;
    // leafSizes[k]: the leaves holding k primitives; empty when the tree is invisible.
    std::vector<size_t> leafSizes;
    std::optional<size_t> bytes;
    // The structure's own figures, printed under the statistics row and in the JSON ("figures").
    std::vector<NamedFigure> figures;
};

// The statistics of `accel`'s last build, the times left 0: a BuildStatsAccelerator's as they are,
// another's (a plugin's) gathered by name; std::invalid_argument for a name unknown or given twice.
BuildStats statisticsOf(const Accelerator& accel);

// Writes `stats` by name (a BuildStatsAccelerator asked through the plugin interface).
void writeStatistics(const BuildStats& stats, BuildStatistics& out);

// An accelerator that computes its statistics as one BuildStats (bvhlab's own do): statisticsOf
// takes them as they are; through the plugin interface they are reported by name.
class BuildStatsAccelerator : public Accelerator {
public:
    // The statistics of the last build, the times left 0.
    virtual BuildStats buildStats() const = 0;
    void statistics(BuildStatistics& out) const final { writeStatistics(buildStats(), out); }
};

}  // namespace bvhlab
