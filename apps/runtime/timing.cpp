#include "apps/runtime/timing.h"

#include "apps/runtime/trace_rays.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>

namespace bvhlab {

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n == 0 ? 0.0 : n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::string_view toString(QueryKind kind) { return kind == QueryKind::Single ? "single" : "batch"; }

namespace {

// One pass over n rays with `threads` threads, in ranges of kQueryRange handed to
// traceRange(begin, end, counters), whose QueryCounters::counting is `counting`; returns passTotal.
template <typename TraceRange>
QueryCounters runPass(tbb::task_arena& arena, size_t n, bool counting, TraceRange&& traceRange) {
    tbb::enumerable_thread_specific<QueryCounters> counters(QueryCounters{.counting = counting});
    const size_t ranges = (n + kQueryRange - 1) / kQueryRange;
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, ranges), [&](const auto& r) {
            for (size_t i = r.begin(); i < r.end(); ++i)
                traceRange(i * kQueryRange, std::min(n, (i + 1) * kQueryRange), counters.local());
        });
    });
    return passTotal(counters, n, counting);
}

// Times `passes` passes over n rays with counting off; beforePass runs outside the timing.
// Then, when `count`, one more pass with counting on, untimed, whose counters are kept.
template <typename BeforePass, typename TraceRange>
PassResult timePasses(size_t n, int threads, int passes, bool count, BeforePass&& beforePass, TraceRange&& traceRange) {
    PassResult result;
    if (n == 0) return result;
    std::vector<double> times, cpuTimes;
    tbb::task_arena arena(threads);
    for (int pass = 0; pass < passes; ++pass) {
        beforePass();
        const auto start = std::chrono::steady_clock::now();
        const double cpuStart = processCpuMs();
        result.counters = runPass(arena, n, /*counting=*/false, traceRange);
        times.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() /
                        double(n));
        cpuTimes.push_back((processCpuMs() - cpuStart) * 1e3 / double(n));
    }
    if (count) {
        beforePass();
        result.counters = runPass(arena, n, /*counting=*/true, traceRange);
    }
    result.usPerQuery = median(times);
    result.cpuUsPerQuery = median(cpuTimes);
    return result;
}

}  // namespace

PassResult tracePasses(const Accelerator& accel, const std::vector<Ray>& rays, bool anyHit, RayCoherence coherence,
                       int threads, int passes, QueryKind kind, bool count) {
    // Into answers allocated outside the timing.
    std::vector<Hit> hits(anyHit ? 0 : rays.size());
    std::vector<uint8_t> occluded(anyHit ? rays.size() : 0);
    const std::span<const Ray> all(rays);
    return timePasses(
        rays.size(), threads, passes, count && accel.hasCounters(), [] {},
        [&](size_t begin, size_t end, QueryCounters& local) {
            if (kind == QueryKind::Single) {
                if (anyHit)
                    for (size_t i = begin; i < end; ++i) occluded[i] = accel.isOccluded(rays[i], local) ? 1 : 0;
                else
                    for (size_t i = begin; i < end; ++i) accel.findNearest(rays[i], hits[i], local);
            } else if (anyHit) {
                accel.isOccludedBatch(all.subspan(begin, end - begin), std::span(occluded).subspan(begin, end - begin),
                                      local, {}, coherence);
            } else {
                accel.findNearestBatch(all.subspan(begin, end - begin), std::span(hits).subspan(begin, end - begin),
                                       local, {}, coherence);
            }
        });
}

PassResult traceNativePasses(NativeRayBatch& batch, bool anyHit, int threads, int passes) {
    return timePasses(
        batch.size(), threads, passes, /*count=*/false, [&] { batch.reset(); },
        [&](size_t begin, size_t end, QueryCounters&) { batch.trace(begin, end, anyHit); });
}

}  // namespace bvhlab
