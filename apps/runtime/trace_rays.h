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

// What a pass over n rays counted, from its threads' counters: their sum when they counted;
// otherwise only the queries, n, since a structure that counts nothing leaves numbers that are
// not its work.
template <typename PerThreadCounters>
QueryCounters passTotal(const PerThreadCounters& perThread, size_t n, bool counting) {
    QueryCounters total{.counting = counting};
    if (!counting) {
        total.queries = n;
        return total;
    }
    for (const QueryCounters& c : perThread) total += c;
    return total;
}

// The loop of traceRays, for rays and answers kept in other layouts (NumPy arrays): calls
// traceRange(begin, end, counters) over [0, n) in ranges of at most kRaysPerRange rays, with
// `threads` threads (0: all hardware threads), each with its thread's counters, whose
// QueryCounters::counting is `counting`; returns passTotal.
QueryCounters forEachRayRange(size_t n, int threads, bool counting,
                              const std::function<void(size_t begin, size_t end, QueryCounters&)>& traceRange);

// Answers every ray (any-hit when `anyHit`) through the batch calls with the hint `coherence`,
// with `threads` threads (0: all hardware threads),
// counting as forEachRayRange says, calling onRange(rays) after each range; returns the counters
// of all threads. A timed pass runs with counting off; N_IT, N_TR and costs come from a pass
// with it on.
QueryCounters traceRays(const Accelerator& accel, std::span<const Ray> rays, bool anyHit, RayCoherence coherence,
                        int threads, bool counting, const RayAnswers& answers,
                        const std::function<void(size_t)>& onRange = {});

}  // namespace bvhlab
