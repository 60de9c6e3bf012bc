// A structure seen through a spy on QueryCounters::counting: it answers as the structure it
// wraps, records the rays asked with counting on and off and the work counted with it on, and
// leaves false numbers (counters and costs) wherever counting is off, as a structure that counts
// nothing may. A caller that took N_IT, N_TR or costs from a call with counting off shows them.
#pragma once

#include "framework/core/accelerator.h"

#include <atomic>

namespace bvhlab::test {

class CountingSpy final : public Accelerator {
public:
    static constexpr uint32_t kFalseWork = 1000003;

    explicit CountingSpy(const Accelerator& inner) : inner_(inner) {}

    const char* name() const override { return inner_.name(); }
    void build(const PrimitiveSet&) override {}
    void statistics(BuildStatistics& out) const override { inner_.statistics(out); }
    bool hasCounters() const override { return inner_.hasCounters(); }

    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override {
        return observe(counters, 1, {}, [&](QueryCounters& c) { return inner_.findNearest(ray, hit, c); });
    }
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override {
        return observe(counters, 1, {}, [&](QueryCounters& c) { return inner_.isOccluded(ray, c); });
    }
    void findNearestBatch(View<const Ray> rays, View<Hit> hits, QueryCounters& counters, View<RayCost> costs,
                          RayCoherence coherence) const override {
        observe(counters, rays.size(), costs, [&](QueryCounters& c) {
            inner_.findNearestBatch(rays, hits, c, costs, coherence);
            return true;
        });
    }
    void isOccludedBatch(View<const Ray> rays, View<uint8_t> occluded, QueryCounters& counters, View<RayCost> costs,
                         RayCoherence coherence) const override {
        observe(counters, rays.size(), costs, [&](QueryCounters& c) {
            inner_.isOccludedBatch(rays, occluded, c, costs, coherence);
            return true;
        });
    }

    // Rays asked with counting on and off, and the work counted with it on (N_IT, N_TR).
    uint64_t countedRays() const { return countedRays_; }
    uint64_t uncountedRays() const { return uncountedRays_; }
    uint64_t countedIntersectionTests() const { return intersectionTests_; }
    uint64_t countedTraversalSteps() const { return traversalSteps_; }

private:
    template <typename Query>
    bool observe(QueryCounters& counters, size_t rays, std::span<RayCost> costs, Query&& query) const {
        QueryCounters own{.counting = counters.counting};
        const bool answer = query(own);
        if (counters.counting) {
            countedRays_ += rays;
            intersectionTests_ += own.intersectionTests;
            traversalSteps_ += own.traversalSteps;
            counters += own;
        } else {
            uncountedRays_ += rays;
            counters.queries += rays;
            counters.intersectionTests += kFalseWork;
            counters.traversalSteps += kFalseWork;
            for (RayCost& cost : costs) cost = {kFalseWork, kFalseWork};
        }
        return answer;
    }

    const Accelerator& inner_;
    mutable std::atomic<uint64_t> countedRays_{0}, uncountedRays_{0}, intersectionTests_{0}, traversalSteps_{0};
};

}  // namespace bvhlab::test
