// What the measuring subcommands (bench, tradeoff) share: medians and timed passes over a ray
// set (see apps/common/accel_config.h for the NAME:Key=value configurations they run).
#pragma once

#include "framework/core/accelerator.h"
#include "framework/core/cpu_clock.h"

#include <vector>

namespace bvhlab {

double median(std::vector<double> values);

struct PassResult {
    double usPerQuery = 0.0;     // median over passes of wall time / queries
    double cpuUsPerQuery = 0.0;  // median over passes of process CPU time / queries (all threads)
    QueryCounters counters;      // of one pass
};

// Answers every ray `passes` times with `threads` threads through the interface's batch calls
// (one per range of 4096 rays); the first pass also counts.
PassResult tracePasses(const Accelerator& accel, const std::vector<Ray>& rays, bool anyHit, int threads, int passes);

// The same passes over a native batch (reset before each pass, untimed); counts queries only.
PassResult traceNativePasses(NativeRayBatch& batch, bool anyHit, int threads, int passes);

}  // namespace bvhlab
