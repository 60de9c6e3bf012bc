// timedBuild, the one clock around Accelerator::build(): it times build() in wall and CPU
// time, and not statistics(), which it calls once, after build(). The double below records when
// its calls ran; the checks are orderings of monotonic clocks, true however loaded the machine.
#include "framework/core/timed_build.h"

#include "framework/core/cpu_clock.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

namespace bvhlab {
namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

// Spins until the process has used `ms` more CPU time.
void burnCpu(double ms) {
    const double start = processCpuMs();
    volatile double sink = 0.0;
    while (processCpuMs() - start < ms) sink = sink + 1.0;
}

// build() sleeps and burns a little; statistics() burns much more (as EPO does) and reports a
// figure of its own. Each records when it started and ended.
class Recorder final : public BuildStatsAccelerator {
public:
    const char* name() const override { return "recorder"; }
    void build(const PrimitiveSet& prims) override {
        calls += "build ";
        buildStart = Clock::now();
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        burnCpu(20.0);
        built = prims.valid.size();
        buildEnd = Clock::now();
    }
    BuildStats buildStats() const override {
        calls += "statistics ";
        statisticsStart = Clock::now();
        statisticsCpuStart = processCpuMs();
        burnCpu(200.0);
        BuildStats stats;
        stats.primitives = built;
        stats.figures = {{"answer", 42.0, "a figure of its own"}};
        return stats;
    }
    bool findNearest(const Ray&, Hit&, QueryCounters&) const override { return false; }
    bool isOccluded(const Ray&, QueryCounters&) const override { return false; }

    size_t built = 0;
    mutable std::string calls;
    Clock::time_point buildStart, buildEnd;
    mutable Clock::time_point statisticsStart;
    mutable double statisticsCpuStart = 0.0;
};

TEST(TimedBuild, TimesBuildAndNotTheStatistics) {
    const std::vector<Triangle> triangles(3);
    const std::vector<uint32_t> valid = {0, 2};
    Recorder accel;
    const Clock::time_point before = Clock::now();
    const double cpuBefore = processCpuMs();
    const BuildStats stats = timedBuild(accel, {triangles, valid});

    EXPECT_EQ(accel.calls, "build statistics ");
    // The statistics' own figures come through.
    EXPECT_EQ(stats.primitives, 2u);
    ASSERT_EQ(stats.figures.size(), 1u);
    EXPECT_EQ(stats.figures[0].value, 42.0);
    // Wall time: at least build()'s, at most up to the start of statistics().
    EXPECT_GE(stats.buildMs, msBetween(accel.buildStart, accel.buildEnd));
    EXPECT_LE(stats.buildMs, msBetween(before, accel.statisticsStart));
    // CPU time: at least build()'s burn, at most what the process used before statistics()
    // began (its 200 ms burn would break this bound).
    EXPECT_GE(stats.buildCpuMs, 20.0);
    EXPECT_LE(stats.buildCpuMs, accel.statisticsCpuStart - cpuBefore);
}

}  // namespace
}  // namespace bvhlab
