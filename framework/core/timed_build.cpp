#include "framework/core/timed_build.h"

#include "framework/core/cpu_clock.h"

#include <chrono>

namespace bvhlab {

namespace {

// The wall and process CPU time of call(), as the statistics' buildMs and buildCpuMs; the
// statistics counted in them when `statisticsTimed`.
template <typename Call>
BuildStats timedStatistics(Accelerator& accel, Call&& call, bool& done, bool statisticsTimed = false) {
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = processCpuMs();
    done = call();
    std::optional<BuildStats> stats;
    if (done && statisticsTimed) stats = statisticsOf(accel);
    const double cpuEnd = processCpuMs();
    const auto end = std::chrono::steady_clock::now();
    if (!done) return {};
    if (!stats) stats = statisticsOf(accel);  // untimed
    stats->buildMs = std::chrono::duration<double, std::milli>(end - start).count();
    stats->buildCpuMs = cpuEnd - cpuStart;
    return *stats;
}

}  // namespace

BuildStats timedBuild(Accelerator& accel, const PrimitiveSet& prims) {
    bool built = false;
    return timedStatistics(
        accel,
        [&] {
            accel.build(prims);
            return true;
        },
        built);
}

std::optional<BuildStats> timedUpdate(Accelerator& accel, const PrimitiveSet& prims, bool statisticsTimed) {
    bool updated = false;
    BuildStats stats = timedStatistics(
        accel, [&] { return accel.update(prims); }, updated, statisticsTimed);
    if (!updated) return std::nullopt;
    return stats;
}

BuildStats timedChange(Accelerator& accel, const std::function<void()>& change) {
    bool changed = false;
    return timedStatistics(
        accel,
        [&] {
            change();
            return true;
        },
        changed);
}

}  // namespace bvhlab
