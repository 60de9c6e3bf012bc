// The interface every acceleration structure implements (nanoGolem style): build over the
// scene's primitives (triangles, spheres, cones), update after they moved, then answer
// closest-hit and any-hit queries, counting its work.
#pragma once

#include <bvhlab/counters.h>
#include <bvhlab/primitive_set.h>
#include <bvhlab/statistics.h>
#include <bvhlab/view.h>

#include <cstdint>

namespace bvhlab {

class Accelerator {
public:
    virtual ~Accelerator() = default;

    // The name it is chosen by: one word.
    virtual const char* name() const = 0;

    // Builds over prims.valid; keeps views of prims' arrays, which must outlive it. Does the
    // build and nothing else: the caller's clocks around this call are T_B.
    virtual void build(const PrimitiveSet& prims) = 0;

    // Updates the structure after its primitives moved, in place of a build: `prims` is the
    // last build's set (or the last update's) with the same index space and the same `valid`,
    // only positions changed (vertices, centres, radii), its arrays possibly new ones, which
    // then must outlive it as build()'s. A primitive that became degenerate stays in `valid` and
    // is never hit. Returns true when the structure now answers for the new positions as a
    // fresh build would (its tree may be worse: statistics() then describe the updated one);
    // false when it has no update, leaving it as it was: the caller then calls build(prims).
    // Another index space or valid set is the caller's error (std::invalid_argument, where
    // the structure can tell). Timed by the caller, as build() is.
    virtual bool update(const PrimitiveSet& /*prims*/) { return false; }

    // Writes the statistics of the last build into `out` (primitives built over, and the tree's
    // figures where it has a tree: nodes, leaves, SAH, EPO, bytes, its own figures). Never
    // timed, so computing them (EPO takes seconds on large scenes) costs T_B nothing.
    virtual void statistics(BuildStatistics& out) const = 0;

    // Closest hit in [ray.tmin, ray.tmax]; on a miss returns false and leaves `hit` unchanged.
    virtual bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const = 0;

    // Any hit in [ray.tmin, ray.tmax], stopping at the first one found.
    virtual bool isOccluded(const Ray& ray, QueryCounters& counters) const = 0;

    // The same queries over a view of rays, answered into a view of the same length: every
    // hits[i] is written (Hit{} on a miss), occluded[i] is 1 or 0. `costs` is empty, or of the
    // same length and receives each ray's work. `coherence` is what the caller knows of the
    // rays (RayCoherence): a hint for choosing a traversal, never a reason to answer otherwise.
    // One call answers its rays on the calling thread (callers split a large batch over
    // threads), counting into `counters` exactly what the single-ray calls would. These defaults
    // loop over the single-ray calls; a structure overrides them to choose its traversal once per
    // batch (bvhlab's BVHs) or to call a native batch API (Embree's stream API). Answers equal the
    // single-ray calls': bvhlab's bit for bit; a native batch API may round differently, within
    // hitsAgree (docs/accuracy.md).
    virtual void findNearestBatch(View<const Ray> rays, View<Hit> hits, QueryCounters& counters, View<RayCost> costs,
                                  RayCoherence /*coherence*/) const {
        for (size_t i = 0; i < rays.size(); ++i) {
            const QueryCounters before = counters;
            Hit hit;
            findNearest(rays[i], hit, counters);
            hits[i] = hit;
            if (!costs.empty()) costs[i] = costBetween(before, counters);
        }
    }
    virtual void isOccludedBatch(View<const Ray> rays, View<uint8_t> occluded, QueryCounters& counters,
                                 View<RayCost> costs, RayCoherence /*coherence*/) const {
        for (size_t i = 0; i < rays.size(); ++i) {
            const QueryCounters before = counters;
            occluded[i] = isOccluded(rays[i], counters) ? 1 : 0;
            if (!costs.empty()) costs[i] = costBetween(before, counters);
        }
    }

    // False when the structure cannot count N_IT and N_TR (they are then reported as unavailable).
    virtual bool hasCounters() const { return true; }

    // A ray's work, from the counters before and after its query: for the batch calls' costs
    // (also those of a structure's SIMD kernels, which are no Accelerator).
    static RayCost costBetween(const QueryCounters& before, const QueryCounters& after) {
        return {uint32_t(after.intersectionTests - before.intersectionTests),
                uint32_t(after.traversalSteps - before.traversalSteps)};
    }
};

}  // namespace bvhlab
