// Answering a batch of rays as `bvhlab raycast` does: ranges of kRaysPerRange rays handed to
// the accelerator's batch calls over a TBB arena of `threads` threads. The Python module
// (apps/python/) answers through it too, so the two trace alike.
#pragma once

#include "framework/core/accelerator.h"

#include <functional>
#include <span>

namespace bvhlab {

inline constexpr size_t kRaysPerRange = 1024;

// What a batch writes: hits for closest-hit queries, occluded (1 or 0) for any-hit ones; costs
// empty or one per ray.
struct RayAnswers {
    std::span<Hit> hits;
    std::span<uint8_t> occluded;
    std::span<RayCost> costs;
};

// The loop of traceRays, for rays and answers kept in other layouts (NumPy arrays): calls
// traceRange(begin, end, counters) over [0, n) in ranges of at most kRaysPerRange rays, with
// `threads` threads (0: all hardware threads), each with its thread's counters; returns their sum.
QueryCounters forEachRayRange(size_t n, int threads,
                              const std::function<void(size_t begin, size_t end, QueryCounters&)>& traceRange);

// Answers every ray (any-hit when `anyHit`) with `threads` threads (0: all hardware threads),
// calling onRange(rays) after each range; returns the counters of all threads.
QueryCounters traceRays(const Accelerator& accel, std::span<const Ray> rays, bool anyHit, int threads,
                        const RayAnswers& answers, const std::function<void(size_t)>& onRange = {});

}  // namespace bvhlab
