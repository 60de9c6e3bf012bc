// The work of queries, counted by the structure that answers them.
#pragma once

#include <bvhlab/quadric_shape.h>

#include <cstdint>

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
        ++(shape.cone() ? coneTests : sphereTests);
    }
};

// The work of one query, for the heat maps: its N_IT and N_TR.
struct RayCost {
    uint32_t intersectionTests = 0;
    uint32_t traversalSteps = 0;
};

}  // namespace bvhlab
