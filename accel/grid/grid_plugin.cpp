// The plugin's entry point: `grid`, Havran's uniform grid, with its keys. Built as
// build/plugins/grid.so and found by name (-DASDS::type=grid); docs/spd.md measures it.
#include "accel/grid/grid_accelerator.h"
#include "accel/grid/grid_env.h"

#include <bvhlab/plugin.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace {

using namespace bvhlab;

Accelerator* createGrid(const PluginSettings& settings) {
    const auto setting = grid::parseGridSetting(settings.getText(keys::Grid::setting.name));
    if (!setting) throw std::invalid_argument("Grid::setting: unknown setting");
    grid::GridParameters parameters{*setting, double(settings.getFloat(keys::Grid::density.name)),
                                    double(settings.getInt(keys::Grid::objects.name)), std::nullopt,
                                    std::string_view(settings.getText(keys::Grid::overlap.name)) == "exact"};
    if (Vec3 r; settings.getVec3(keys::Grid::resolution.name, r)) {
        const auto cells = [](float v) { return int(std::clamp(std::round(v), 1.0f, float(grid::kMaxAxisCells))); };
        parameters.fixed = grid::GridResolution{cells(r.x), cells(r.y), cells(r.z)};
    }
    return new grid::GridAccelerator(parameters);
}

}  // namespace

BVHLAB_PLUGIN(registrar) {
    using namespace bvhlab;
    registrar.addAccelerator(
        {"grid",
         "Havran's uniform grid: Woo's resolution, 3D-DDA, no mailboxes (a plugin: accel/grid/, docs/spd.md)",
         {keys::Grid::density, keys::Grid::setting, keys::Grid::objects, keys::Grid::resolution, keys::Grid::overlap},
         createGrid});
}
