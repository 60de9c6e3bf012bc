#include "accel/grid/grid_resolution.h"

#include <algorithm>
#include <cmath>

namespace bvhlab::grid {

std::optional<GridSetting> parseGridSetting(std::string_view name) {
    if (name == "woo") return GridSetting::Woo;
    if (name == "regular") return GridSetting::Regular;
    if (name == "heterogeneous") return GridSetting::Heterogeneous;
    return std::nullopt;
}

namespace {

int cellsOf(double value) {
    if (!(value >= 1.0)) return 1;  // also NaN
    return int(std::min(std::floor(value + 0.5), double(kMaxAxisCells)));
}

GridResolution woo(double cellsWanted, const DVec3& size, const bool flat[3]) {
    double volume = 1.0;
    int active = 0;
    for (int a = 0; a < 3; ++a) {
        if (flat[a]) continue;
        volume *= size[a];
        ++active;
    }
    GridResolution res;
    if (active == 0) return res;
    const double side = std::pow(volume / cellsWanted, 1.0 / active);  // of a cubic cell
    int r[3] = {1, 1, 1};
    for (int a = 0; a < 3; ++a)
        if (!flat[a]) r[a] = cellsOf(size[a] / side);
    return {r[0], r[1], r[2]};
}

}  // namespace

GridResolution gridResolution(GridSetting setting, double density, double objects, const DVec3& size) {
    const double cellsWanted = density * objects;
    const double longest = std::max({size.x, size.y, size.z});
    if (!(cellsWanted >= 1.0) || !(longest > 0.0) || !std::isfinite(longest)) return {};
    bool flat[3];
    bool anyFlat = false;
    for (int a = 0; a < 3; ++a) anyFlat |= (flat[a] = !(size[a] > kFlatAxis * longest));

    switch (setting) {
        case GridSetting::Regular: {
            const int r = cellsOf(density * std::cbrt(objects));
            return {flat[0] ? 1 : r, flat[1] ? 1 : r, flat[2] ? 1 : r};
        }
        case GridSetting::Heterogeneous: {
            if (anyFlat) return woo(cellsWanted, size, flat);
            const double v = cellsWanted;
            const int x = cellsOf(std::cbrt(v * size.x * size.x / (size.y * size.z)));
            const int y = cellsOf(std::sqrt(v * size.y / (double(x) * size.z)));
            const int z = cellsOf(v / (double(x) * double(y)));
            return {x, y, z};
        }
        case GridSetting::Woo:
        default:
            return woo(cellsWanted, size, flat);
    }
}

}  // namespace bvhlab::grid
