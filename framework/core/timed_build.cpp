#include "framework/core/timed_build.h"

#include "framework/core/cpu_clock.h"

#include <chrono>

namespace bvhlab {

BuildStats timedBuild(Accelerator& accel, const PrimitiveSet& prims) {
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = processCpuMs();
    accel.build(prims);
    const double cpuEnd = processCpuMs();
    const auto end = std::chrono::steady_clock::now();
    BuildStats stats = statisticsOf(accel);
    stats.buildMs = std::chrono::duration<double, std::milli>(end - start).count();
    stats.buildCpuMs = cpuEnd - cpuStart;
    return stats;
}

}  // namespace bvhlab
