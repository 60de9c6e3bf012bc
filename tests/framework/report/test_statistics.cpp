// The statistics row: a structure's own figures (BuildStats::figures) and every counter of
// kQueryCounters reach the table and the JSON.
#include "framework/report/statistics.h"

#include "framework/report/query_counters_json.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <set>

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

// Every counter of the table, and no other, is in the JSON of each kind of query as its mean per
// query, and every counter with a column is printed: a counter added to the table needs no edit here.
TEST(Statistics, EveryCounterOfTheTableIsPrintedAndInTheJson) {
    StatsRow row;
    QueryCounters& counters = row.render.primary.counters;
    counters.queries = 4;
    uint64_t value = 8;
    for (const QueryCounter& c : kQueryCounters) counters.*c.count = value, value += 4;
    const nlohmann::json primary = statsJson(row)["primary"];
    std::set<std::string> keys = {"queries", "t_r_us"}, written;
    for (const QueryCounter& c : kQueryCounters) {
        keys.insert(c.key);
        EXPECT_EQ(primary[c.key], double(counters.*c.count) / 4.0) << c.key;
    }
    for (const auto& [key, v] : primary.items()) written.insert(key);
    EXPECT_EQ(written, keys);
    std::set<std::string> tableKeys, writerKeys;  // the writer of bench, builders, tradeoff and spd
    for (const QueryCounter& c : kQueryCounters) tableKeys.insert(c.key);
    const nlohmann::json writerJson = queryCountersJson(counters, 4.0, true);
    for (const auto& [key, v] : writerJson.items()) writerKeys.insert(key);
    EXPECT_EQ(writerKeys, tableKeys);

    const std::string table = formatStatsTable(row);
    const std::string header = table.substr(0, table.find('\n'));
    const std::string primaryLine =
        table.substr(header.size() + 1, table.find('\n', header.size() + 1) - header.size() - 1);
    for (const QueryCounter& c : kQueryCounters) {
        if (!c.column) continue;
        EXPECT_NE(header.find(std::string(" ") + c.column + " "), std::string::npos) << c.column << "\n" << table;
        EXPECT_NE(primaryLine.find(fmt::format(" {:.2f} ", double(counters.*c.count) / 4.0)), std::string::npos)
            << c.column << "\n"
            << table;
    }
}

// Nothing counted (a structure without counters, or no query traced): every counter is null.
TEST(Statistics, CountersOfAStructureThatCountsNothingAreNull) {
    StatsRow row;
    row.hasCounters = false;
    row.render.primary.counters.queries = 3;
    const nlohmann::json j = statsJson(row);
    for (const QueryCounter& c : kQueryCounters) {
        EXPECT_TRUE(j["primary"][c.key].is_null()) << c.key;
        EXPECT_TRUE(j["shadow"][c.key].is_null()) << c.key;
    }
}

}  // namespace
}  // namespace bvhlab
