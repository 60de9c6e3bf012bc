#include "accel/octree/octree_accelerator.h"

#include <bvhlab/reference_tests.h>

#include <vector>

namespace bvhlab::octree {

std::optional<Traversal> parseTraversal(std::string_view name) {
    if (name == "octree84") return Traversal::Octree84;
    if (name == "octree93") return Traversal::Octree93;
    return std::nullopt;
}

void OctreeAccelerator::build(const PrimitiveSet& prims) {
    prims_ = prims;
    tree_ = buildOctree(prims, parameters_);
    countedQueries_ = 0;
    leavesVisited_ = 0;
    emptyLeavesVisited_ = 0;
}

void OctreeAccelerator::statistics(BuildStatistics& out) const {
    out.set("primitives", double(prims_.valid.size()));
    const uint64_t leaves = tree_.leaves(), refs = tree_.references();
    out.set("nodes", double(tree_.nodes.size()));
    out.set("leaves", double(leaves));
    out.set("avg_leaf_prims", leaves > 0 ? double(tree_.refs.size()) / double(leaves) : 0.0);
    out.set("max_leaf_prims", double(tree_.maxLeafReferences()));
    out.set("max_depth", double(tree_.deepestLeaf));
    out.set("bytes", double(tree_.bytes()));
    std::vector<size_t> sizes(tree_.maxLeafReferences() + 1, 0);
    for (const OctreeNode& n : tree_.nodes)
        if (n.isLeaf()) ++sizes[n.references()];
    if (!tree_.nodes.empty()) out.leafSizes(sizes);
    out.figure("N_IN", double(tree_.innerNodes()), "inner nodes (Havran)");
    out.figure("N_V", double(leaves), "leaves, the elementary cells (Havran)");
    out.figure("N_EV", double(tree_.emptyLeaves()), "empty leaves (Havran)");
    out.figure("N_OIV", double(refs), "object references in the leaves (Havran; a polygon is one object)");
    out.figure("objects", double(tree_.objects), "objects built over: primitives, a polygon's fan of triangles one");
    if (const uint64_t queries = countedQueries_.load(); queries > 0) {
        out.figure("N_ETS", double(leavesVisited_.load()) / double(queries),
                   "leaves visited per ray, over the counted queries since the build (Havran)");
        out.figure("N_EETS", double(emptyLeavesVisited_.load()) / double(queries),
                   "empty leaves visited per ray, over the counted queries since the build (Havran)");
    }
}

template <typename Visit>
void OctreeAccelerator::walk(const Ray& ray, QueryCounters& counters, Visit&& visit) const {
    const ClippedRay clipped(tree_, ray);
    uint64_t leaves = 0, empty = 0;
    if (clipped.hits()) {
        const auto counted = [&](uint32_t leaf, double exit) {
            const OctreeNode& node = tree_.nodes[leaf];
            ++leaves;
            empty += node.objects == 0;
            return visit(tree_.leafReferences(node), exit);
        };
        if (traversal_ == Traversal::Octree84)
            walkOctree84(tree_, clipped, counters.traversalSteps, counted);
        else
            walkOctree93(tree_, clipped, counters.traversalSteps, counted);
    }
    if (counters.counting) {
        countedQueries_.fetch_add(1, std::memory_order_relaxed);
        leavesVisited_.fetch_add(leaves, std::memory_order_relaxed);
        emptyLeavesVisited_.fetch_add(empty, std::memory_order_relaxed);
    }
}

// Every point of a primitive lies in each leaf its closed box touches, which refers to it.
bool OctreeAccelerator::findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const {
    ++counters.queries;
    if (!ray.isValid() || tree_.nodes.empty()) return false;
    return findNearestAlong(
        prims_, ray, counters, [&](auto&& visit) { walk(ray, counters, visit); }, hit);
}

bool OctreeAccelerator::isOccluded(const Ray& ray, QueryCounters& counters) const {
    ++counters.queries;
    if (!ray.isValid() || tree_.nodes.empty()) return false;
    return isOccludedAlong(prims_, ray, counters, [&](auto&& visit) { walk(ray, counters, visit); });
}

}  // namespace bvhlab::octree
