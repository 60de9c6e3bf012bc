// The env keys of the `grid` plugin.
#pragma once

#include "framework/config/env.h"

#include <string_view>

namespace bvhlab::keys::Grid {
inline constexpr std::string_view kSettings[] = {"woo", "regular", "heterogeneous"};
inline constexpr FloatKey density{"Grid::density", "1", 0.001, 1000,
                                  "voxel density D: the grid has about D*N cells for N objects (Havran: usually 1)"};
inline constexpr ChoiceKey setting{
    "Grid::setting", "woo", kSettings,
    "resolution method of Havran's text: woo (D*N cubic cells), regular (D*N^(1/3) per axis), "
    "heterogeneous (Klimaszewski's formulas)"};
inline constexpr IntKey objects{"Grid::objects", "0", 0, 2000000000,
                                "N for the resolution: 0 counts the primitives built over; give the NFF object "
                                "count to size the grid as Havran did (docs/spd.md)"};
inline constexpr std::string_view kOverlaps[] = {"box", "exact"};
inline constexpr ChoiceKey overlap{
    "Grid::overlap", "box", kOverlaps,
    "which cells reference a primitive: box (those its bounding box overlaps, as Havran's figures show he did) or "
    "exact (triangle-box separating axes, sphere-box distance; cones by their box)"};
inline constexpr Vec3Key resolution{"Grid::resolution", "",
                                   "cells per axis (x y z), instead of the setting's: to build at a published "
                                   "resolution (docs/spd.md); not given: the setting decides"};
}  // namespace bvhlab::keys::Grid
