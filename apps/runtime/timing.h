// What the measuring subcommands (bench, tradeoff) share: medians and timed passes over a ray
// set (see apps/runtime/accel_config.h for the NAME:Key=value configurations they run).
#pragma once

#include "framework/core/accelerator.h"
#include "framework/core/cpu_clock.h"

#include <string_view>
#include <vector>

namespace bvhlab {

double median(std::vector<double> values);

struct PassResult {
    double usPerQuery = 0.0;     // median over passes of wall time / queries
    double cpuUsPerQuery = 0.0;  // median over passes of process CPU time / queries (all threads)
    QueryCounters counters;      // of the counting pass; without one, only a pass's queries
};

// How a structure is asked: ray by ray through findNearest / isOccluded (single), or through the
// batch calls findNearestBatch / isOccludedBatch, one call per range of kQueryRange rays (batch),
// with the set's coherence hint.
enum class QueryKind { Single, Batch };

std::string_view toString(QueryKind kind);  // "single", "batch"

// The rays of a pass are split over the threads in ranges of this many (the last one shorter),
// each starting at a multiple of it: a batch call's size, and whole packets of 8 or 16 rays.
constexpr size_t kQueryRange = 4096;

// Answers every ray `passes` times with `threads` threads, asked as `kind` says, with counting
// off (QueryCounters::counting), timed; then, when `count` and the structure counts, once more
// with counting on, untimed, in the same ranges: N_IT and N_TR of the same rays.
PassResult tracePasses(const Accelerator& accel, const std::vector<Ray>& rays, bool anyHit, RayCoherence coherence,
                       int threads, int passes, QueryKind kind, bool count = true);

// The same timed passes over a native batch (reset before each pass, untimed), one trace() per
// range; counts queries only.
PassResult traceNativePasses(NativeRayBatch& batch, bool anyHit, int threads, int passes);

}  // namespace bvhlab
