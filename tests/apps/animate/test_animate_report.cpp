// The summary table and the per-frame CSV of `bvhlab animate`, on a hand-written results file
// whose totals, worst frames and ratios are worked out in tests/support/animate_results.h.
#include "apps/animate/animate_report.h"
#include "tests/support/animate_results.h"

#include <gtest/gtest.h>

#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace bvhlab::test {
namespace {

using nlohmann::json;

// The Markdown table's rows by contender, each cell by its column's header.
std::map<std::string, std::map<std::string, std::string>> summaryRowsByLabel(const std::string& markdown) {
    std::vector<std::vector<std::string>> lines;
    std::stringstream in(markdown);
    for (std::string line; std::getline(in, line);) {
        if (!line.starts_with("| ")) continue;
        std::vector<std::string> cells;
        for (size_t at = 2, end; (end = line.find(" |", at)) != std::string::npos; at = end + 3)
            cells.push_back(line.substr(at, end - at));
        lines.push_back(cells);
    }
    std::map<std::string, std::map<std::string, std::string>> rows;
    for (size_t i = 1; i < lines.size(); ++i)
        for (size_t c = 0; c < lines[0].size(); ++c) rows[lines[i][0]][lines[0][c]] = lines[i][c];
    return rows;
}

// The CSV's lines split into fields, a quoted field unquoted.
std::vector<std::vector<std::string>> framesCsvCells(const std::string& csv) {
    std::vector<std::vector<std::string>> lines;
    std::stringstream in(csv);
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> cells(1);
        bool quoted = false;
        for (size_t i = 0; i < line.size(); ++i) {
            if (line[i] == '"' && quoted && i + 1 < line.size() && line[i + 1] == '"')
                cells.back() += '"', ++i;
            else if (line[i] == '"')
                quoted = !quoted;
            else if (line[i] == ',' && !quoted)
                cells.emplace_back();
            else
                cells.back() += line[i];
        }
        lines.push_back(cells);
    }
    return lines;
}

json withoutCheck(json results) {
    for (json& contender : results["contenders"])
        for (json& row : contender["rows"]) row.erase("agreement");
    return results;
}

TEST(AnimateReport, SummaryTotalsWorstFramesAndSahDrift) {
    auto rows = summaryRowsByLabel(animateSummaryTable(smallAnimateResults()));
    ASSERT_EQ(rows.size(), 6u);
    auto& refit = rows["sahbvh8/refit"];
    EXPECT_EQ(refit["frames"], "3");
    EXPECT_EQ(refit["rebuilds"], "0");
    EXPECT_EQ(refit["T_update [ms]"], "34.000");
    EXPECT_EQ(refit["T_R p+s [ms]"], "54.000");
    EXPECT_EQ(refit["total [ms]"], "88.000");
    EXPECT_EQ(refit["per frame [ms]"], "29.333");
    EXPECT_EQ(refit["worst frame [ms]"], "0 (45.000)");
    EXPECT_EQ(refit["SAH last / first"], "x1.20");
    EXPECT_EQ(refit["N_IT / ray"], "25.00");
    EXPECT_EQ(refit["N_TR / ray"], "5.00");
    EXPECT_EQ(refit["bytes"], "1000");

    auto& adaptive = rows["sahbvh8/adaptive"];
    EXPECT_EQ(adaptive["rebuilds"], "1");  // frame 20; frame 0's build is not counted
    EXPECT_EQ(adaptive["total [ms]"], "200.000");
    EXPECT_EQ(adaptive["worst frame [ms]"], "20 (135.000)");
    EXPECT_EQ(adaptive["SAH last / first"], "x1.02");
    EXPECT_EQ(adaptive["bytes"], "1200");  // the last frame's

    auto& embreeLow = rows["embree-low/rebuild"];
    EXPECT_EQ(embreeLow["rebuilds"], "2");
    EXPECT_EQ(embreeLow["total [ms]"], "115.000");
    EXPECT_EQ(embreeLow["worst frame [ms]"], "20 (39.000)");
    EXPECT_EQ(embreeLow["SAH last / first"], "");  // Embree reports no SAH
    EXPECT_EQ(embreeLow["N_IT / ray"], "");
    EXPECT_EQ(embreeLow["N_TR / ray"], "");
}

TEST(AnimateReport, SummaryRatiosToTheFastestEmbreeAndTheFastestContender) {
    const std::string table = animateSummaryTable(smallAnimateResults());
    auto rows = summaryRowsByLabel(table);
    // embree-refit/refit (97 ms) is the fastest Embree contender, sahbvh8/refit (88 ms) the fastest.
    EXPECT_EQ(rows["sahbvh8/refit"]["/ fastest Embree"], "0.91");
    EXPECT_EQ(rows["sahbvh8/refit"]["/ fastest"], "1.00");
    EXPECT_EQ(rows["sahbvh8/adaptive"]["/ fastest Embree"], "2.06");
    EXPECT_EQ(rows["sahbvh8/adaptive"]["/ fastest"], "2.27");
    EXPECT_EQ(rows["embree-refit/refit"]["/ fastest Embree"], "1.00");
    EXPECT_EQ(rows["embree-refit/refit"]["/ fastest"], "1.10");
    EXPECT_EQ(rows["embree-low/rebuild"]["/ fastest Embree"], "1.19");
    EXPECT_EQ(rows["embree-low/rebuild"]["/ fastest"], "1.31");
    EXPECT_NE(table.find("\nFastest: sahbvh8/refit (88.000 ms); fastest Embree contender: embree-refit/refit (97.000 "
                         "ms). Totals are over every measured frame, the first (the build) included;"),
              std::string::npos)
        << table;
}

TEST(AnimateReport, SummaryFailedOrSkippedContenderIsARowWithTheReasonOutsideTheRatios) {
    json results = smallAnimateResults();
    auto rows = summaryRowsByLabel(animateSummaryTable(results));
    EXPECT_EQ(rows["embree-low/refit"]["frames"], "skipped: Embree at low quality has no refit");
    EXPECT_EQ(rows["embree-low/refit"]["/ fastest Embree"], "");
    EXPECT_EQ(rows["kdtree/rebuild"]["frames"], "failed: threw: kdtree \\| cannot be updated, no refit");
    EXPECT_EQ(rows["kdtree/rebuild"]["total [ms]"], "");
    EXPECT_EQ(rows["kdtree/rebuild"]["/ fastest"], "");
    // Its partial first frame (40 ms, faster than any total) sets no yardstick.
    EXPECT_EQ(rows["sahbvh8/refit"]["/ fastest"], "1.00");

    // No Embree contender measured: the ratio to Embree is blank and the line says so.
    results["contenders"][2]["failed"] = "crashed: SIGSEGV";
    results["contenders"][3]["failed"] = "crashed: SIGSEGV";
    const std::string table = animateSummaryTable(results);
    EXPECT_EQ(summaryRowsByLabel(table)["sahbvh8/refit"]["/ fastest Embree"], "");
    EXPECT_NE(table.find("fastest Embree contender: none measured."), std::string::npos) << table;
}

TEST(AnimateReport, SummaryCountsWrongAnswersOnlyWhenChecked) {
    auto rows = summaryRowsByLabel(animateSummaryTable(smallAnimateResults()));
    EXPECT_EQ(rows["sahbvh8/refit"]["wrong"], "1");
    EXPECT_EQ(rows["sahbvh8/adaptive"]["wrong"], "1");
    EXPECT_EQ(rows["embree-refit/refit"]["wrong"], "0");
    EXPECT_EQ(rows["embree-low/rebuild"]["wrong"], "");  // not checked

    rows = summaryRowsByLabel(animateSummaryTable(withoutCheck(smallAnimateResults())));
    EXPECT_FALSE(rows["sahbvh8/refit"].contains("wrong"));
}

TEST(AnimateReport, FramesCsvHasARowPerContenderAndFrame) {
    const auto lines = framesCsvCells(animateFramesCsv(smallAnimateResults()));
    const std::vector<std::string> header = {
        "label", "accel",     "policy", "frame", "time", "action", "update_ms", "primary_ms", "shadow_ms", "total_ms",
        "sah",   "sah_ratio", "epo",    "n_it",  "n_tr", "bytes",  "wrong",     "failed",     "skipped"};
    // Four contenders' three frames; the skipped one's reason; the failed one's partial frame and reason.
    ASSERT_EQ(lines.size(), 1u + 4 * 3 + 1 + 2);
    EXPECT_EQ(lines[0], header);
    for (const auto& line : lines) EXPECT_EQ(line.size(), header.size()) << line[0];

    // sahbvh8/adaptive at frame 20: the rebuild, its SAH back near frame 0's.
    EXPECT_EQ(lines[6], (std::vector<std::string>{"sahbvh8/adaptive", "sahbvh8", "adaptive", "20", "2", "rebuild",
                                                  "120.0000", "10.0000", "5.0000", "135.0000", "51.000000", "1.020000",
                                                  "10.000000", "25.000", "5.000", "1200", "0", "", ""}));
    // Embree: no SAH, EPO or counters, empty cells; embree-low was not checked.
    EXPECT_EQ(lines[7],
              (std::vector<std::string>{"embree-refit/refit", "embree-refit", "refit", "0", "0", "build", "50.0000",
                                        "8.0000", "4.0000", "62.0000", "", "", "", "", "", "2000", "0", "", ""}));
    EXPECT_EQ(lines[12][0], "embree-low/rebuild");
    EXPECT_EQ(lines[12][16], "");
    EXPECT_EQ(lines[13],
              (std::vector<std::string>{"embree-low/refit", "embree-low", "refit", "", "", "", "", "", "", "", "", "",
                                        "", "", "", "", "", "", "Embree at low quality has no refit"}));
    EXPECT_EQ(lines[14], (std::vector<std::string>{"kdtree/rebuild", "kdtree", "rebuild", "0", "0", "build", "40.0000",
                                                   "", "", "", "", "", "", "", "", "", "", "", ""}));
    EXPECT_EQ(lines[15],
              (std::vector<std::string>{"kdtree/rebuild", "kdtree", "rebuild", "", "", "", "", "", "", "", "", "", "",
                                        "", "", "", "", "threw: kdtree | cannot be updated, no refit", ""}));

    const auto unchecked = framesCsvCells(animateFramesCsv(withoutCheck(smallAnimateResults())));
    EXPECT_EQ(unchecked[0].size(), header.size() - 1);
    EXPECT_EQ(unchecked[0][16], "failed");
}

}  // namespace
}  // namespace bvhlab::test
