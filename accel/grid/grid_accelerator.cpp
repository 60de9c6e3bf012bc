#include "accel/grid/grid_accelerator.h"

#include "accel/grid/grid_traversal.h"

#include <bvhlab/reference_tests.h>

namespace bvhlab::grid {

void GridAccelerator::build(const PrimitiveSet& prims) {
    prims_ = prims;
    grid_ = buildGridCells(prims, parameters_);
}

void GridAccelerator::statistics(BuildStatistics& out) const {
    out.set("primitives", double(prims_.valid.size()));
    const uint64_t cells = grid_.cells(), empty = grid_.emptyCells(), refs = grid_.references();
    // A grid has no tree: its cells are the leaves (nodes = leaves = N_V, empty ones included),
    // and nothing of a tree's depth or SAH applies.
    out.set("nodes", double(cells));
    out.set("leaves", double(cells));
    out.set("avg_leaf_prims", cells > 0 ? double(refs) / double(cells) : 0.0);
    out.set("max_leaf_prims", double(grid_.maxCellReferences()));
    out.set("bytes", double(grid_.bytes()));
    out.figure("res_x", double(grid_.res.x), "cells along x");
    out.figure("res_y", double(grid_.res.y), "cells along y");
    out.figure("res_z", double(grid_.res.z), "cells along z");
    out.figure("N_V", double(cells), "elementary cells (Havran)");
    out.figure("N_EV", double(empty), "empty elementary cells (Havran)");
    out.figure("N_OIV", double(refs), "object references in the elementary cells (Havran)");
    out.figure("D", grid_.densityUsed, "density used: Grid::density, or less where the reference budget lowered it");
}

namespace {

// The references of cell c.
View<const uint32_t> cellReferences(const GridCells& g, size_t c) {
    return {g.refs.data() + g.cellStart[c], size_t(g.cellStart[c + 1] - g.cellStart[c])};
}

// The cells along the ray, each counted in N_TS (our N_TR). Cells are closed and enlarged
// (grid_cells.h), so a hit on a face is referenced by the cell before it.
auto cellWalk(const GridCells& g, const Ray& ray, QueryCounters& counters) {
    return [&g, &ray, &counters](auto&& visit) {
        walkCells(g, ray, [&](size_t c, double exit) {
            ++counters.traversalSteps;
            return visit(cellReferences(g, c), exit);
        });
    };
}

}  // namespace

bool GridAccelerator::findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const {
    ++counters.queries;
    if (!ray.isValid() || grid_.refs.empty()) return false;
    return findNearestAlong(prims_, ray, counters, cellWalk(grid_, ray, counters), hit);
}

bool GridAccelerator::isOccluded(const Ray& ray, QueryCounters& counters) const {
    ++counters.queries;
    if (!ray.isValid() || grid_.refs.empty()) return false;
    return isOccludedAlong(prims_, ray, counters, cellWalk(grid_, ray, counters));
}

}  // namespace bvhlab::grid
