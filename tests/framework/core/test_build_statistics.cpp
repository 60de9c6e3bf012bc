// The statistics of a build reported by name (<bvhlab/statistics.h>) and gathered into a
// BuildStats (framework/core/accelerator.h): every field through its name and back, and a name
// bvhlab does not know, a count that is no count or a statistic given twice refused.
#include "framework/core/accelerator.h"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace bvhlab;

namespace {

// Reports `stats`, or what `write` writes.
class Reporting final : public Accelerator {
public:
    explicit Reporting(void (*write)(BuildStatistics&)) : write_(write) {}
    const char* name() const override { return "reporting"; }
    void build(const PrimitiveSet&) override {}
    void statistics(BuildStatistics& out) const override { write_(out); }
    bool findNearest(const Ray&, Hit&, QueryCounters&) const override { return false; }
    bool isOccluded(const Ray&, QueryCounters&) const override { return false; }

private:
    void (*write_)(BuildStatistics&);
};

BuildStats everyField() {
    BuildStats stats;
    stats.primitives = 10;
    stats.nodes = 7;
    stats.leaves = 4;
    stats.avgLeafPrimitives = 2.5;
    stats.maxLeafPrimitives = 4;
    stats.maxDepth = 3;
    stats.depthBound = 64;
    stats.leafBound = 8;
    stats.sah = SahCost{12.5, 1.0, 2.0};
    stats.epo = 0.25;
    stats.leafSizes = {0, 1, 2, 0, 1};
    stats.bytes = 4096;
    stats.figures = {{"voxels", 27, "cells of the grid"}};
    return stats;
}

TEST(BuildStatistics, EveryFieldGoesByItsNameAndComesBack) {
    const Reporting accel([](BuildStatistics& out) { writeStatistics(everyField(), out); });
    const BuildStats back = statisticsOf(accel);
    const BuildStats sent = everyField();
    EXPECT_EQ(back.primitives, sent.primitives);
    EXPECT_EQ(back.nodes, sent.nodes);
    EXPECT_EQ(back.leaves, sent.leaves);
    EXPECT_EQ(back.avgLeafPrimitives, sent.avgLeafPrimitives);
    EXPECT_EQ(back.maxLeafPrimitives, sent.maxLeafPrimitives);
    EXPECT_EQ(back.maxDepth, sent.maxDepth);
    EXPECT_EQ(back.depthBound, sent.depthBound);
    EXPECT_EQ(back.leafBound, sent.leafBound);
    ASSERT_TRUE(back.sah);
    EXPECT_EQ(back.sah->cost, 12.5);
    EXPECT_EQ(back.sah->cIntersect, 2.0);
    EXPECT_EQ(back.epo, sent.epo);
    EXPECT_EQ(back.leafSizes, sent.leafSizes);
    EXPECT_EQ(back.bytes, sent.bytes);
    ASSERT_EQ(back.figures.size(), 1u);
    EXPECT_EQ(back.figures[0].name, "voxels");
    EXPECT_EQ(back.figures[0].meaning, "cells of the grid");
    EXPECT_EQ(back.buildMs, 0.0);
}

TEST(BuildStatistics, StatisticsNotReportedStayUnset) {
    const BuildStats stats = statisticsOf(Reporting([](BuildStatistics& out) { out.set("primitives", 3); }));
    EXPECT_EQ(stats.primitives, 3u);
    EXPECT_FALSE(stats.nodes);
    EXPECT_FALSE(stats.sah);
    EXPECT_TRUE(stats.leafSizes.empty());
}

TEST(BuildStatistics, AnUnknownNameANonCountOrARepeatIsRefusedNamingIt) {
    auto refusal = [](void (*write)(BuildStatistics&)) -> std::string {
        try {
            statisticsOf(Reporting(write));
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(refusal([](BuildStatistics& out) { out.set("node", 3); }),
              "reporting: unknown statistic 'node' (a figure of its own is reported with figure())");
    EXPECT_EQ(refusal([](BuildStatistics& out) { out.set("leaves", 2.5); }),
              "reporting: statistic 'leaves' = 2.5 is not a count");
    EXPECT_EQ(refusal([](BuildStatistics& out) {
                  out.set("nodes", 3);
                  out.set("nodes", 4);
              }),
              "reporting: statistic 'nodes' given twice");
    EXPECT_EQ(refusal([](BuildStatistics& out) { out.figure("two words", 1, "?"); }),
              "reporting: figure name 'two words' is not one word");
}

}  // namespace
