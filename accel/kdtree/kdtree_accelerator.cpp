#include "accel/kdtree/kdtree_accelerator.h"

#include "accel/kdtree/kdtree_traversal.h"

#include <bvhlab/reference_tests.h>

#include <vector>

namespace bvhlab::kdtree {

void KdTreeAccelerator::build(const PrimitiveSet& prims) {
    prims_ = prims;
    tree_ = buildKdTree(prims, parameters_);
}

void KdTreeAccelerator::statistics(BuildStatistics& out) const {
    const double references = double(tree_.references.size()), leaves = double(tree_.leaves);
    out.set("primitives", double(prims_.valid.size()));
    out.set("nodes", double(tree_.nodes.size()));
    out.set("leaves", leaves);
    out.set("avg_leaf_prims", leaves > 0 ? references / leaves : 0.0);
    out.set("max_leaf_prims", double(tree_.maxLeafReferences));
    out.set("max_depth", double(tree_.deepestLeaf));
    out.set("depth_bound", double(tree_.maxDepth + 1));
    out.set("bytes", double(tree_.bytes()));
    // The SAH with C_trav = C_isect = 1, as bvhlab's BVHs report theirs by default, so that the
    // columns compare; the cost the build minimised (K_T, K_I) is a figure of its own.
    out.set("sah", sahCost(tree_, 1.0, 1.0));
    out.set("sah_c_trav", 1.0);
    out.set("sah_c_isect", 1.0);
    out.figure("empty_leaves", double(tree_.emptyLeaves), "leaves that hold no primitive");
    out.figure("references", references,
               "primitive references in the leaves (a primitive is in each leaf it overlaps)");
    out.figure("references_per_primitive", prims_.valid.empty() ? 0.0 : references / double(prims_.valid.size()),
               "references over primitives");
    out.figure("sah_kt_ki", sahCost(tree_, parameters_.cTraversal / parameters_.cIntersect, 1.0),
               "the SAH the build minimised, K_T / K_I per traversal step and 1 per primitive test");
    out.figure("max_depth_key", double(tree_.maxDepth),
               "the depth bound the build kept to (KdTree::maxDepth or its rule)");
    out.figure("events_swept", double(tree_.eventsSwept),
               "events over all nodes' sweeps: the build's work, O(N log N)");
    std::vector<size_t> leavesOfSize(tree_.maxLeafReferences + 1, 0);
    for (const KdNode& n : tree_.nodes)
        if (n.isLeaf()) ++leavesOfSize[n.references()];
    out.leafSizes(leavesOfSize);
}

namespace {

// A ray whose origin or direction is not finite has no interval to walk: it is tested against
// every primitive, as the reference does, so that it gets the reference's answer.
bool walkable(const Ray& ray) { return isFinite(ray.org) && isFinite(ray.dir); }

View<const uint32_t> leafReferences(const KdTree& tree, const KdNode& leaf) {
    return {tree.references.data() + leaf.firstReference(), leaf.references()};
}

}  // namespace

bool KdTreeAccelerator::findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const {
    ++counters.queries;
    if (!ray.isValid() || tree_.nodes.empty()) return false;
    const ShearedRay sheared(ray);
    float tmax = ray.tmax;
    Hit best;
    auto keep = [&](float t, uint32_t prim, float u, float v) {
        best = {t, prim, u, v};
        return false;  // a closer hit may follow
    };
    if (walkable(ray)) {
        walkLeaves(tree_, ray, tmax, counters, [&](const KdNode& leaf) {
            testReferences(prims_, leafReferences(tree_, leaf), ray, sheared, tmax, counters, keep);
            return false;  // the walk skips what lies beyond the closest hit
        });
    } else {
        testReferences(prims_, prims_.valid, ray, sheared, tmax, counters, keep);
    }
    if (!best.found()) return false;
    hit = best;
    return true;
}

bool KdTreeAccelerator::isOccluded(const Ray& ray, QueryCounters& counters) const {
    ++counters.queries;
    if (!ray.isValid() || tree_.nodes.empty()) return false;
    const ShearedRay sheared(ray);
    float tmax = ray.tmax;
    bool occluded = false;
    auto stop = [&](float, uint32_t, float, float) { return occluded = true; };
    if (walkable(ray)) {
        walkLeaves(tree_, ray, tmax, counters, [&](const KdNode& leaf) {
            return testReferences(prims_, leafReferences(tree_, leaf), ray, sheared, tmax, counters, stop);
        });
    } else {
        testReferences(prims_, prims_.valid, ray, sheared, tmax, counters, stop);
    }
    return occluded;
}

}  // namespace bvhlab::kdtree
