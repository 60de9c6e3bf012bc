// The work of queries, counted by the structure that answers them.
#pragma once

#include <bvhlab/quadric_shape.h>

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <type_traits>

namespace bvhlab {

// The uint64 slots of QueryCounters, queries and the counters of kQueryCounters: a fixed number,
// so that a plugin compiled before a counter was added still agrees with bvhlab on the struct.
inline constexpr size_t kQueryCounterSlots = 16;

// Work done by queries, in Havran's terms. One instance per thread, passed into every
// query, merged after the run: no atomics, no sharing on the hot path.
//
// `counting` asks for the counts. Counting costs a timed query time (a counter update per node
// and per leaf), so a structure may keep a form of its queries that counts nothing and run it
// when `counting` is false (bvhlab's BVHs do: docs/architecture.md, "Counting"); the numbers it
// leaves then are not its work. Timed passes turn it off, and N_IT and N_TR come from a pass
// over the same rays with it on. A structure that always counts may ignore it.
//
// Adding a counter: declare it in place of the first unused slot (one fewer unused), add it in
// addWork and give it a row of kQueryCounters; the reports, JSON and Python list it from there. A counter keeps its
// slot for good (never removed, never moved), so the size and every offset stay as plugins compiled earlier saw them:
// such a plugin leaves the new counter at 0, and the plugin ABI does not change.
struct QueryCounters {
    uint64_t queries = 0;
    uint64_t intersectionTests = 0;                // N_IT: ray-primitive tests, every kind
    uint64_t traversalSteps = 0;                   // N_TR: nodes visited
    uint64_t sphereTests = 0;                      // the part of N_IT that tested spheres ...
    uint64_t coneTests = 0;                        // ... and cones (the rest tested triangles)
    uint64_t unused[kQueryCounterSlots - 5] = {};  // the slots of counters to come
    bool counting = true;                          // see above; not a count: += and addWork leave it

    // Adds o's work (every counter of kQueryCounters), not its queries: for a query answered by
    // several structures.
    void addWork(const QueryCounters& o);
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

// One counter of the work of queries, as every report names it.
struct QueryCounter {
    const char* key;                 // the JSON key of its mean per query
    const char* column;              // its column in printed tables, or nullptr: JSON only
    uint64_t QueryCounters::*count;  // its slot
    const char* meaning;
};

// The counters of QueryCounters but queries (the count they are divided by), in slot order: the
// one list the statistics, every JSON writer and the Python bindings read.
inline constexpr QueryCounter kQueryCounters[] = {
    {"n_it", "N_IT", &QueryCounters::intersectionTests, "ray-primitive tests, every kind"},
    {"n_tr", "N_TR", &QueryCounters::traversalSteps, "nodes visited"},
    {"n_it_sphere", nullptr, &QueryCounters::sphereTests, "the part of N_IT that tested spheres"},
    {"n_it_cone", nullptr, &QueryCounters::coneTests, "the part of N_IT that tested cones and cylinders"},
};

static_assert(sizeof(QueryCounters) == (kQueryCounterSlots + 1) * sizeof(uint64_t) &&
                  offsetof(QueryCounters, counting) == kQueryCounterSlots * sizeof(uint64_t),
              "QueryCounters is kQueryCounterSlots uint64 slots, then counting");
static_assert(1 + std::size(kQueryCounters) + std::extent_v<decltype(QueryCounters::unused)> == kQueryCounterSlots,
              "every counter declared in QueryCounters has a row of kQueryCounters");

// Listed by hand, as the compiler merges these additions into vector ones and does not merge
// additions through kQueryCounters' member pointers (tests/framework/api/test_counters.cpp checks
// that every row is added).
inline void QueryCounters::addWork(const QueryCounters& o) {
    intersectionTests += o.intersectionTests;
    traversalSteps += o.traversalSteps;
    sphereTests += o.sphereTests;
    coneTests += o.coneTests;
}

// The work of one query, for the heat maps: its N_IT and N_TR.
struct RayCost {
    uint32_t intersectionTests = 0;
    uint32_t traversalSteps = 0;
};

}  // namespace bvhlab
