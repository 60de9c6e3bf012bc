#include "accel/grid/grid_accelerator.h"

#include "accel/grid/grid_traversal.h"

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

// Tests every reference of cell `c` in [ray.tmin, tmax]; onHit(t, prim, u, v) returns true to stop.
template <typename OnHit>
bool testCell(const GridCells& g, const PrimitiveSet& prims, size_t c, const Ray& ray, const ShearedRay& sheared,
              float& tmax, QueryCounters& counters, OnHit&& onHit) {
    for (uint32_t i = g.cellStart[c]; i < g.cellStart[c + 1]; ++i) {
        const uint32_t prim = g.refs[i];
        if (prims.kind(prim) == PrimitiveKind::Triangle) {
            ++counters.intersectionTests;
            TriangleHitT<float> h;
            if (intersectTriangle(sheared, prims.triangles[prim], ray.tmin, tmax, h)) {
                tmax = h.t;
                if (onHit(h.t, prim, h.u, h.v)) return true;
            }
        } else {
            const QuadricShape shape = prims.quadric(prim);
            counters.countQuadricTest(shape);
            QuadricHitT<float> h;
            if (intersectQuadric(ray, shape, ray.tmin, tmax, h)) {
                tmax = h.t;
                if (onHit(h.t, prim, 0.0f, 0.0f)) return true;
            }
        }
    }
    return false;
}

}  // namespace

bool GridAccelerator::findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const {
    ++counters.queries;
    if (!ray.isValid() || grid_.refs.empty()) return false;
    const ShearedRay sheared(ray);
    float tmax = ray.tmax;
    Hit best;
    walkCells(grid_, ray, [&](size_t c, double exit) {
        ++counters.traversalSteps;
        testCell(grid_, prims_, c, ray, sheared, tmax, counters, [&](float t, uint32_t prim, float u, float v) {
            best = {t, prim, u, v};
            return false;
        });
        // A hit beyond this cell's exit is kept (tmax) but answered only once the walk reaches
        // its cell: a closer one may lie in the cells between. Cells are closed and enlarged
        // (grid_cells.h), so a hit on a face is referenced by the cell before it.
        return !(best.found() && double(best.t) <= exit);
    });
    if (!best.found()) return false;
    hit = best;
    return true;
}

bool GridAccelerator::isOccluded(const Ray& ray, QueryCounters& counters) const {
    ++counters.queries;
    if (!ray.isValid() || grid_.refs.empty()) return false;
    const ShearedRay sheared(ray);
    float tmax = ray.tmax;
    bool occluded = false;
    walkCells(grid_, ray, [&](size_t c, double) {
        ++counters.traversalSteps;
        occluded = testCell(grid_, prims_, c, ray, sheared, tmax, counters,
                            [](float, uint32_t, float, float) { return true; });
        return !occluded;
    });
    return occluded;
}

}  // namespace bvhlab::grid
