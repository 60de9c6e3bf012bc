#include "apps/runtime/trace_rays.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace bvhlab {

QueryCounters forEachRayRange(size_t n, int threads, bool counting,
                              const std::function<void(size_t begin, size_t end, QueryCounters&)>& traceRange) {
    tbb::enumerable_thread_specific<QueryCounters> perThread(QueryCounters{.counting = counting});
    tbb::task_arena(threads > 0 ? threads : tbb::info::default_concurrency()).execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kRaysPerRange),
                          [&](const auto& range) { traceRange(range.begin(), range.end(), perThread.local()); });
    });
    return passTotal(perThread, n, counting);
}

QueryCounters traceRays(const Accelerator& accel, std::span<const Ray> rays, bool anyHit, RayCoherence coherence,
                        int threads, bool counting, const RayAnswers& answers,
                        const std::function<void(size_t)>& onRange) {
    return forEachRayRange(rays.size(), threads, counting, [&](size_t begin, size_t end, QueryCounters& counters) {
        const size_t size = end - begin;
        const std::span<RayCost> costs = answers.costs.empty() ? answers.costs : answers.costs.subspan(begin, size);
        if (anyHit)
            accel.isOccludedBatch(rays.subspan(begin, size), answers.occluded.subspan(begin, size), counters, costs,
                                  coherence);
        else
            accel.findNearestBatch(rays.subspan(begin, size), answers.hits.subspan(begin, size), counters, costs,
                                   coherence);
        if (onRange) onRange(size);
    });
}

}  // namespace bvhlab
