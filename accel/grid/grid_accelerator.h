// Havran's uniform grid (../shared/reference/spd/havran_stats_grids.txt) as an Accelerator:
// the cells of grid_cells.h, walked by the 3D-DDA of grid_traversal.h, every reference of a
// cell tested with bvhlab's watertight tests. A plugin (grid_plugin.cpp), not linked into bvhlab.
#pragma once

#include "accel/grid/grid_cells.h"

#include <bvhlab/accelerator.h>

namespace bvhlab::grid {

class GridAccelerator final : public Accelerator {
public:
    explicit GridAccelerator(const GridParameters& parameters) : parameters_(parameters) {}

    const char* name() const override { return "grid"; }
    void build(const PrimitiveSet& prims) override;
    void statistics(BuildStatistics& out) const override;
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override;
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override;

    const GridCells& cells() const { return grid_; }

private:
    GridParameters parameters_;
    PrimitiveSet prims_;
    GridCells grid_;
};

}  // namespace bvhlab::grid
