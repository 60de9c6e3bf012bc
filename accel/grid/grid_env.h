// The env keys of the `grid` plugin.
#pragma once

#include <bvhlab/settings.h>

namespace bvhlab::keys::Grid {
inline constexpr const char* kSettings[] = {"woo", "regular", "heterogeneous"};
inline constexpr PluginKey density{"Grid::density",
                                   KeyType::Float,
                                   "1",
                                   "voxel density D: the grid has about D*N cells for N objects (Havran: usually 1)",
                                   0.001,
                                   1000};
inline constexpr PluginKey setting{"Grid::setting",
                                   KeyType::Choice,
                                   "woo",
                                   "resolution method of Havran's text: woo (D*N cubic cells), regular (D*N^(1/3) per "
                                   "axis), heterogeneous (Klimaszewski's formulas)",
                                   0,
                                   0,
                                   kSettings};
inline constexpr PluginKey objects{"Grid::objects",
                                   KeyType::Int,
                                   "0",
                                   "N for the resolution: 0 counts the primitives built over; give the NFF object "
                                   "count to size the grid as Havran did (docs/spd.md)",
                                   0,
                                   2000000000};
inline constexpr const char* kOverlaps[] = {"box", "exact"};
inline constexpr PluginKey overlap{
    "Grid::overlap",
    KeyType::Choice,
    "box",
    "which cells reference a primitive: box (those its bounding box overlaps, as Havran's figures show he did) or "
    "exact (triangle-box separating axes, sphere-box distance; cones by their box)",
    0,
    0,
    kOverlaps};
inline constexpr PluginKey resolution{"Grid::resolution", KeyType::Vec3, "",
                                      "cells per axis (x y z), instead of the setting's: to build at a published "
                                      "resolution (docs/spd.md); not given: the setting decides"};
}  // namespace bvhlab::keys::Grid
