// The grid's resolution from the number of objects N, the density D and the scene box, by the
// three methods of Havran and Sixta's grid comparison (../shared/reference/spd/
// havran_stats_grids.txt, "Uniform Grid"): regular, Woo's and heterogeneous (docs/spd.md,
// "The uniform grid").
#pragma once

#include <bvhlab/math.h>

#include <cstdint>
#include <optional>
#include <string_view>

namespace bvhlab::grid {

enum class GridSetting { Woo, Regular, Heterogeneous };

// The setting named by the key Grid::setting ("woo", "regular", "heterogeneous").
std::optional<GridSetting> parseGridSetting(std::string_view name);

struct GridResolution {
    int x = 1, y = 1, z = 1;
    int operator[](int axis) const { return axis == 0 ? x : (axis == 1 ? y : z); }
    uint64_t cells() const { return uint64_t(x) * uint64_t(y) * uint64_t(z); }
    bool operator==(const GridResolution&) const = default;
};

// An axis shorter than this fraction of the longest is flat: it gets one cell, and the other
// axes share the D*N cells (a scene of one quad is a 2D grid).
inline constexpr double kFlatAxis = 1e-6;
// No axis gets more cells than this.
inline constexpr int kMaxAxisCells = 1 << 14;

// The resolution for N objects at density D in a box of the given extent:
// - Woo: V = D*N cells, as cubic as the box allows: the cell side s = (sx*sy*sz / V)^(1/3)
//   and each axis gets round(size/s) cells (at least 1). Havran's listing of Woo's method
//   computes the same ratios from the longest side but truncates; its printed resolutions are
//   those of cubic cells rounded to nearest (docs/spd.md).
// - Regular: every axis gets round(D * N^(1/3)) cells, whatever the box.
// - Heterogeneous (Klimaszewski), the text's formulas, rounded as it rounds (+0.5):
//   xres = (V*sx*sx/(sy*sz))^(1/3), yres = (V*sy/(xres*sz))^(1/2), zres = V/(xres*yres).
// Flat axes (kFlatAxis) get 1 cell under every setting; a heterogeneous grid with a flat axis
// is Woo's over the others (its formulas divide by the flat side).
GridResolution gridResolution(GridSetting setting, double density, double objects, const DVec3& size);

}  // namespace bvhlab::grid
