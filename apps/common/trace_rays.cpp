#include "apps/common/trace_rays.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace bvhlab {

QueryCounters traceRays(const Accelerator& accel, std::span<const Ray> rays, bool anyHit, int threads,
                        const RayAnswers& answers, const std::function<void(size_t)>& onRange) {
    tbb::enumerable_thread_specific<QueryCounters> perThread;
    tbb::task_arena(threads > 0 ? threads : tbb::info::default_concurrency()).execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), kRaysPerRange), [&](const auto& range) {
            const size_t begin = range.begin(), size = range.size();
            const std::span<RayCost> costs = answers.costs.empty() ? answers.costs : answers.costs.subspan(begin, size);
            if (anyHit)
                accel.isOccludedBatch(rays.subspan(begin, size), answers.occluded.subspan(begin, size),
                                      perThread.local(), costs);
            else
                accel.findNearestBatch(rays.subspan(begin, size), answers.hits.subspan(begin, size), perThread.local(),
                                       costs);
            if (onRange) onRange(size);
        });
    });
    QueryCounters total;
    for (const QueryCounters& c : perThread) total += c;
    return total;
}

}  // namespace bvhlab
