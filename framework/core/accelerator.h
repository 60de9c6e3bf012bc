// The interface every acceleration structure implements (nanoGolem style): build over the
// scene's primitives (triangles, spheres, cones), then answer closest-hit and any-hit
// queries, counting its work.
#pragma once

#include "framework/core/native_ray_batch.h"
#include "framework/core/primitive_set.h"

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace bvhlab {

// Work done by queries, in Havran's terms. One instance per thread, passed into every
// query, merged after the run: no atomics, no sharing on the hot path.
//
// `counting` asks for the counts. Counting costs a timed query time (a counter update per node
// and per leaf), so a structure may keep a form of its queries that counts nothing and run it
// when `counting` is false (bvhlab's BVHs do: docs/architecture.md, "Counting"); the numbers it
// leaves then are not its work. Timed passes turn it off, and N_IT and N_TR come from a pass
// over the same rays with it on. A structure that always counts may ignore it.
struct QueryCounters {
    uint64_t queries = 0;
    uint64_t intersectionTests = 0;  // N_IT: ray-primitive tests, every kind
    uint64_t traversalSteps = 0;     // N_TR: nodes visited
    uint64_t sphereTests = 0;        // the part of N_IT that tested spheres ...
    uint64_t coneTests = 0;          // ... and cones (the rest tested triangles)
    bool counting = true;            // see above; not a count: += and addWork leave it

    // Adds o's work, not its queries: for a query answered by several structures.
    void addWork(const QueryCounters& o) {
        intersectionTests += o.intersectionTests;
        traversalSteps += o.traversalSteps;
        sphereTests += o.sphereTests;
        coneTests += o.coneTests;
    }
    QueryCounters& operator+=(const QueryCounters& o) {
        queries += o.queries;
        addWork(o);
        return *this;
    }
    uint64_t triangleTests() const { return intersectionTests - sphereTests - coneTests; }
    // One ray-quadric test, counted in N_IT and by its kind.
    void countQuadricTest(const QuadricShape& shape) {
        ++intersectionTests;
        ++(std::holds_alternative<Sphere>(shape) ? sphereTests : coneTests);
    }
};

// The work of one query, for the heat maps: its N_IT and N_TR.
struct RayCost {
    uint32_t intersectionTests = 0;
    uint32_t traversalSteps = 0;
};

// SAH cost normalised by the root box: C_trav * sum over inner nodes of A(n)/A(root)
// + C_isect * sum over leaves of A(l)/A(root) * N(l). The constants are stated with it.
struct SahCost {
    double cost = 0.0;
    double cTraversal = 1.0;
    double cIntersect = 1.0;
};

// A figure of a structure's own, beside the common ones: a grid's resolution and references
// per voxel, a kd-tree's empty leaves.
struct NamedFigure {
    std::string name;     // one word, as the JSON key: "voxels"
    double value = 0.0;
    std::string meaning;  // one line: "N_V, cells of the grid"
};

// What a build reports: its times, measured by the caller around build() (timed_build.h), and
// the structure's statistics(). Structures without a visible tree (Embree) leave the tree
// fields unset: unavailable, not zero.
struct BuildStats {
    // T_B in wall time, and the process's CPU time over the same call (all threads). Left 0
    // by statistics(): the caller times build(), so every structure is timed alike.
    double buildMs = 0.0;
    double buildCpuMs = 0.0;
    size_t primitives = 0;  // primitives built over (degenerate ones excluded)
    std::optional<size_t> nodes;  // all nodes, leaves included
    std::optional<size_t> leaves;
    std::optional<double> avgLeafPrimitives;
    std::optional<size_t> maxLeafPrimitives;
    std::optional<int> maxDepth;
    // The depth the structure promises to stay below (its traversal stacks hold that many
    // levels), and the most primitives it promises a leaf holds; unset where it promises none.
    // Checked by `bvhlab stress` and the stress tests, which hold a structure to what it
    // promises and every structure to bounded build time and memory; not reported.
    std::optional<int> depthBound;
    std::optional<size_t> leafBound;
    std::optional<SahCost> sah;
    // End-point overlap (Aila, Karras and Laine 2013) with the SAH's constants: the area of
    // geometry inside node boxes but not in their subtrees, by node cost, over all geometry's
    // area. Unset where the tree is invisible or it was not computed (large scenes).
    std::optional<double> epo;
    // leafSizes[k]: the leaves holding k primitives; empty when the tree is invisible.
    std::vector<size_t> leafSizes;
    std::optional<size_t> bytes;
    // The structure's own figures, printed under the statistics row and in the JSON ("figures").
    std::vector<NamedFigure> figures;
};

class Accelerator {
public:
    virtual ~Accelerator() = default;

    virtual std::string_view name() const = 0;

    // Builds over prims.valid; keeps views of prims' arrays, which must outlive it. Does the
    // build and nothing else: the caller's clocks around this call are T_B (timed_build.h).
    virtual void build(const PrimitiveSet& prims) = 0;

    // The statistics of the last build (primitives built over, and the tree's figures where it
    // has a tree: nodes, leaves, SAH, EPO, bytes, its own figures), leaving the times 0. Never
    // timed, so computing them (EPO takes seconds on large scenes) costs T_B nothing.
    virtual BuildStats statistics() const = 0;

    // Closest hit in [ray.tmin, ray.tmax]; on a miss returns false and leaves `hit` unchanged.
    virtual bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const = 0;

    // Any hit in [ray.tmin, ray.tmax], stopping at the first one found.
    virtual bool isOccluded(const Ray& ray, QueryCounters& counters) const = 0;

    // The same queries over a span of rays, answered into a span of the same length: every
    // hits[i] is written (Hit{} on a miss), occluded[i] is 1 or 0. `costs` is empty, or of the
    // same length and receives each ray's work. One call answers its rays on the calling thread
    // (callers split a large batch over threads), counting into `counters` exactly what the
    // single-ray calls would. These defaults loop over the single-ray calls; a structure
    // overrides them to choose its traversal once per batch (ours) or to call a native batch
    // API (Embree's stream API). Answers equal the single-ray calls': ours bit for bit; a native
    // batch API may round differently, within hitsAgree (docs/accuracy.md).
    virtual void findNearestBatch(std::span<const Ray> rays, std::span<Hit> hits, QueryCounters& counters,
                                  std::span<RayCost> costs) const {
        for (size_t i = 0; i < rays.size(); ++i) {
            const QueryCounters before = counters;
            Hit hit;
            findNearest(rays[i], hit, counters);
            hits[i] = hit;
            if (!costs.empty()) costs[i] = costBetween(before, counters);
        }
    }
    virtual void isOccludedBatch(std::span<const Ray> rays, std::span<uint8_t> occluded, QueryCounters& counters,
                                 std::span<RayCost> costs) const {
        for (size_t i = 0; i < rays.size(); ++i) {
            const QueryCounters before = counters;
            occluded[i] = isOccluded(rays[i], counters) ? 1 : 0;
            if (!costs.empty()) costs[i] = costBetween(before, counters);
        }
    }

    // False when the structure cannot count N_IT and N_TR (they are then reported as unavailable).
    virtual bool hasCounters() const { return true; }

    // The rays in the structure's own format, for a bare loop of its native call after build();
    // nullptr when it has no other API than this interface (ours). Throws std::invalid_argument
    // naming the first ray the native call cannot take as it is.
    virtual std::unique_ptr<NativeRayBatch> prepareNativeBatch(const std::vector<Ray>& /*rays*/) const {
        return nullptr;
    }

    // A ray's work, from the counters before and after its query: for the batch calls' costs
    // (also those of a structure's SIMD kernels, which are no Accelerator).
    static RayCost costBetween(const QueryCounters& before, const QueryCounters& after) {
        return {uint32_t(after.intersectionTests - before.intersectionTests),
                uint32_t(after.traversalSteps - before.traversalSteps)};
    }
};

}  // namespace bvhlab
