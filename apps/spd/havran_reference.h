// Havran's published statistics of GOLEM on the SPD scenes (../shared/reference/spd/:
// havran_stats_grids.txt, havran_stats_octrees.txt), read from those files as published: the
// ray invariants per scene; per scene every table of both files (his grids and octrees by
// method), each row with its value per column; and per scene the grid and the octree with the
// fewest intersection tests per ray (N_IT, with that structure's N_TS).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bvhlab {

struct HavranBest {
    double nIt = 0.0, nTs = 0.0;
};

// One scene's part of one of Havran's tables: by row name without its unit ("N_IT", "T_B"), the
// value in each column (an octree table's columns are the maximum depths 4, 5, 6, 7).
using HavranTable = std::map<std::string, std::vector<double>>;

struct HavranScene {
    std::map<std::string, double> invariants;  // by Havran's names: PrimaryRay, ..., IntersRequired
    std::optional<HavranBest> bestGrid, bestOctree;
    // By the title of the table's section: "Uniform Grid", "Octree84-C", "Octree93-A", ...
    std::map<std::string, HavranTable> tables;
};

// By scene name in lower case (balls, mount, ...). Throws InputError naming the file when a
// file is missing or holds no invariants table.
std::map<std::string, HavranScene> readHavranReference(const std::filesystem::path& folder);

// The invariants in the order of Havran's table.
inline constexpr const char* kHavranInvariants[] = {"PrimaryRay",   "UsedIntPrimRay", "ShadowRay", "UsedIntShadRay",
                                                    "SecondaryRay", "UsedIntSecRay",  "AllRays",   "IntersRequired"};

// The rows of his octree tables that bvhlab measures (the octree plugin's figures and the spd
// command's N_IT and N_TS), in his order, and the first maximum depth of his columns.
inline constexpr const char* kHavranOctreeRows[] = {"N_IN", "N_V", "N_EV", "N_OIV", "N_IT", "N_TS", "N_ETS", "N_EETS"};
inline constexpr int kHavranFirstDepth = 4;

}  // namespace bvhlab
