// A structure that answers every query as a miss without looking at its ray: `bvhlab bench`'s
// `nothing` rows, the part of every row's T_R that is the interface's own (the virtual call, the
// caller's loop, counting the query, writing the answer) and no structure's. Its batch calls
// write the answers and count, the least any structure's batch call does.
#pragma once

#include "framework/core/accelerator.h"

#include <algorithm>

namespace bvhlab {

class NothingAccelerator final : public BuildStatsAccelerator {
public:
    const char* name() const override { return "nothing"; }
    void build(const PrimitiveSet&) override {}
    BuildStats buildStats() const override { return {}; }
    bool findNearest(const Ray&, Hit&, QueryCounters& counters) const override {
        ++counters.queries;
        return false;
    }
    bool isOccluded(const Ray&, QueryCounters& counters) const override {
        ++counters.queries;
        return false;
    }
    void findNearestBatch(View<const Ray> rays, View<Hit> hits, QueryCounters& counters, View<RayCost> costs,
                          RayCoherence) const override {
        std::fill(hits.begin(), hits.end(), Hit{});
        std::fill(costs.begin(), costs.end(), RayCost{});
        counters.queries += rays.size();
    }
    void isOccludedBatch(View<const Ray> rays, View<uint8_t> occluded, QueryCounters& counters, View<RayCost> costs,
                         RayCoherence) const override {
        std::fill(occluded.begin(), occluded.end(), uint8_t(0));
        std::fill(costs.begin(), costs.end(), RayCost{});
        counters.queries += rays.size();
    }
};

}  // namespace bvhlab
