// Havran's octree (octree_nodes.h) as an Accelerator: walked by either traversal of
// octree_traversal.h, every reference of a leaf tested with bvhlab's watertight tests. A plugin
// (octree_plugin.cpp), not linked into bvhlab.
#pragma once

#include "accel/octree/octree_nodes.h"
#include "accel/octree/octree_traversal.h"

#include <bvhlab/accelerator.h>

#include <atomic>

namespace bvhlab::octree {

class OctreeAccelerator final : public Accelerator {
public:
    OctreeAccelerator(const OctreeParameters& parameters, Traversal traversal)
        : parameters_(parameters), traversal_(traversal) {}

    const char* name() const override { return "octree"; }
    void build(const PrimitiveSet& prims) override;
    // Havran's figures of the structure, and those per ray (N_ETS, N_EETS) of the queries since
    // the build that counted (QueryCounters::counting).
    void statistics(BuildStatistics& out) const override;
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override;
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override;

    const Octree& tree() const { return tree_; }

private:
    // Calls visit(references, tExit) for the leaves along the ray with the chosen traversal,
    // counting N_TS, and the leaves and empty leaves it visits.
    template <typename Visit>
    void walk(const Ray& ray, QueryCounters& counters, Visit&& visit) const;

    OctreeParameters parameters_;
    Traversal traversal_;
    PrimitiveSet prims_;
    Octree tree_;
    // Leaves visited (N_ETS), empty ones (N_EETS), by the counting queries since the build.
    mutable std::atomic<uint64_t> countedQueries_{0}, leavesVisited_{0}, emptyLeavesVisited_{0};
};

}  // namespace bvhlab::octree
