// The statistics row: a structure's own figures (BuildStats::figures) reach the table and the JSON.
#include "framework/report/statistics.h"

#include <gtest/gtest.h>

namespace bvhlab {
namespace {

TEST(Statistics, AStructuresOwnFiguresArePrintedAndInTheJson) {
    StatsRow row;
    row.scene = "teapots";
    row.accel = "grid";
    row.build.figures = {{"voxels", 4096, "N_V, cells of the grid"}, {"refs_per_voxel", 2.5, "N_OIV"}};
    const std::string table = formatStatsTable(row);
    EXPECT_NE(table.find("grid voxels: 4096 (N_V, cells of the grid)"), std::string::npos) << table;
    EXPECT_NE(table.find("grid refs_per_voxel: 2.5 (N_OIV)"), std::string::npos) << table;
    const nlohmann::json j = statsJson(row);
    EXPECT_EQ(j["figures"]["voxels"]["value"], 4096.0);
    EXPECT_EQ(j["figures"]["refs_per_voxel"]["meaning"], "N_OIV");
    EXPECT_TRUE(statsJson(StatsRow{})["figures"].empty());
}

}  // namespace
}  // namespace bvhlab
