// The plugin's entry point: `grid`, Havran's uniform grid, with its keys. Built as
// build/plugins/grid.so and found by name (-DASDS::type=grid); docs/spd.md measures it.
#include "accel/grid/grid_accelerator.h"
#include "accel/grid/grid_env.h"
#include "framework/plugin/plugin_api.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

BVHLAB_PLUGIN(registrar) {
    using namespace bvhlab;
    registrar.addAccelerator(
        {"grid", "Havran's uniform grid: Woo's resolution, 3D-DDA, no mailboxes (a plugin: accel/grid/, docs/spd.md)",
         {keys::Grid::density.declaration(), keys::Grid::setting.declaration(), keys::Grid::objects.declaration(),
          keys::Grid::resolution.declaration(), keys::Grid::overlap.declaration()},
         [](const Env& env) -> std::unique_ptr<Accelerator> {
             const auto setting = grid::parseGridSetting(env.get(keys::Grid::setting));
             if (!setting) throw std::invalid_argument("Grid::setting: unknown setting");
             grid::GridParameters parameters{*setting, double(env.get(keys::Grid::density)),
                                             double(env.get(keys::Grid::objects)), std::nullopt,
                                             env.get(keys::Grid::overlap) == "exact"};
             if (const std::optional<Vec3> r = env.get(keys::Grid::resolution)) {
                 const auto cells = [](float v) { return int(std::clamp(std::round(v), 1.0f, float(grid::kMaxAxisCells))); };
                 parameters.fixed = grid::GridResolution{cells(r->x), cells(r->y), cells(r->z)};
             }
             return std::make_unique<grid::GridAccelerator>(parameters);
         }});
}
