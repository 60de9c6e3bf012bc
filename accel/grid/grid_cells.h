// The grid's cells and their object references: every primitive is referenced in each cell it
// overlaps, tested conservatively (docs/spd.md, "The uniform grid"). Either by its bounding box
// (GridParameters::exactOverlap false, Havran's rule: his N_OIV and N_EV on tetra at 35^3 are
// those of bounding boxes to the reference), or exactly:
// - triangles by the separating-axis test of triangle and box (Akenine-Möller 2001: the box's
//   three axes, the triangle's normal, the nine edge-by-axis cross products), in double;
// - spheres by the distance from the centre to the box against the radius, in double;
// - cones (and cylinders) by their bounding box against the cell's.
// Each cell is enlarged by kCellMargin of its side (and a margin for float coordinates) before
// the test, so a primitive touching a cell's face, or within rounding of it, is referenced on
// both sides: no point of a primitive lies in a cell that does not reference it.
#pragma once

#include "accel/grid/grid_resolution.h"

#include <bvhlab/primitive_set.h>

#include <cstdint>
#include <optional>
#include <vector>

namespace bvhlab::grid {

inline constexpr double kCellMargin = 1e-4;

// A bound on the references a build makes (the cells of each primitive's box), beyond which the
// density is halved until it fits: bounded time and memory on any input.
inline constexpr uint64_t kMinReferenceBudget = uint64_t(1) << 24;
inline constexpr uint64_t kReferencesPerPrimitive = 32;
inline constexpr uint64_t kMaxCells = uint64_t(1) << 24;

struct GridCells {
    DVec3 lower{0.0}, upper{0.0};  // the grid's box: the primitives' bounds, padded
    DVec3 cellSize{1.0};
    DVec3 inverseCellSize{1.0};
    GridResolution res;
    // The references of cell c are refs[cellStart[c] .. cellStart[c + 1]), ascending.
    std::vector<uint32_t> cellStart{0, 0};
    std::vector<uint32_t> refs;
    double densityUsed = 0.0;  // below the asked density when the budget lowered it

    size_t cellIndex(int x, int y, int z) const {
        return (size_t(z) * size_t(res.y) + size_t(y)) * size_t(res.x) + size_t(x);
    }
    uint64_t cells() const { return res.cells(); }
    uint64_t emptyCells() const;                         // Havran's N_EV
    uint64_t references() const { return refs.size(); }  // Havran's N_OIV
    size_t maxCellReferences() const;
    size_t bytes() const { return cellStart.size() * sizeof(uint32_t) + refs.size() * sizeof(uint32_t); }
};

// The exact extent of the valid primitives' bounds (empty box: no valid primitive).
Bounds3 primitiveBounds(const PrimitiveSet& prims);

// How the resolution is chosen: Havran's N (0: the number of valid primitives), the density
// and setting of gridResolution(), or a fixed resolution that overrides them.
struct GridParameters {
    GridSetting setting = GridSetting::Woo;
    double density = 1.0;
    double objects = 0.0;
    std::optional<GridResolution> fixed;
    bool exactOverlap = false;  // false: a primitive's bounding box decides (Havran)
};

// Builds the grid over prims.valid. Where the reference budget is exceeded, the density (or a
// fixed resolution's cells, by the same factor) is halved until it fits.
GridCells buildGridCells(const PrimitiveSet& prims, const GridParameters& parameters);

// The overlap tests, for the tests: does the primitive touch the closed box [lo, hi]?
bool triangleOverlapsBox(const Triangle& tri, const DVec3& lo, const DVec3& hi);
bool sphereOverlapsBox(const Sphere& sphere, const DVec3& lo, const DVec3& hi);

}  // namespace bvhlab::grid
