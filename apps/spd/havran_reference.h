// Havran's published statistics of GOLEM on the SPD scenes (../shared/reference/spd/:
// havran_stats_grids.txt, havran_stats_octrees.txt), read from those files as published: the
// ray invariants per scene, and per scene the grid and the octree with the fewest
// intersection tests per ray (N_IT, with that structure's N_TS).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace bvhlab {

struct HavranBest {
    double nIt = 0.0, nTs = 0.0;
};

struct HavranScene {
    std::map<std::string, double> invariants;  // by Havran's names: PrimaryRay, ..., IntersRequired
    std::optional<HavranBest> bestGrid, bestOctree;
};

// By scene name in lower case (balls, mount, ...). Throws InputError naming the file when a
// file is missing or holds no invariants table.
std::map<std::string, HavranScene> readHavranReference(const std::filesystem::path& folder);

// The invariants in the order of Havran's table.
inline constexpr const char* kHavranInvariants[] = {"PrimaryRay",    "UsedIntPrimRay", "ShadowRay", "UsedIntShadRay",
                                                     "SecondaryRay",  "UsedIntSecRay",  "AllRays",   "IntersRequired"};

}  // namespace bvhlab
