#include "accel/bvh/builders/cluster_tree.h"

#include "accel/bvh/builders/binned_sah_builder.h"
#include "accel/bvh/builders/build_jobs.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace bvhlab {

namespace {

float halfArea(const ClusterBox& b) {
    const float dx = b.upper[0] - b.lower[0], dy = b.upper[1] - b.lower[1], dz = b.upper[2] - b.lower[2];
    return dx * dy + dy * dz + dz * dx;
}

}  // namespace

void ClusterTree::resize(uint32_t leaves) {
    const size_t nodes = 2 * size_t(leaves) - 1;
    leafCount = leaves;
    boxes.resize(nodes);
    children.resize(2 * (size_t(leaves) - 1));
    prims.resize(nodes), height.resize(nodes), cost.resize(nodes), leaf.resize(nodes);
}

void formNode(ClusterTree& tree, uint32_t node, const BuildConfig& config) {
    const float area = halfArea(tree.boxes[node]);
    if (node < tree.leafCount) {
        tree.prims[node] = 1, tree.height[node] = 0, tree.leaf[node] = 1;
        tree.cost[node] = config.cIntersect * float(config.sahTests(1)) * area;
        return;
    }
    const uint32_t l = tree.children[2 * size_t(node - tree.leafCount)];
    const uint32_t r = tree.children[2 * size_t(node - tree.leafCount) + 1];
    const uint32_t prims = tree.prims[l] + tree.prims[r];
    const float asInner = config.cTraversal * area + tree.cost[l] + tree.cost[r];
    const float asLeaf = config.cIntersect * float(config.sahTests(prims)) * area;
    const bool leaf = prims <= uint32_t(config.maxLeaf) ||
                      (config.sahTermination && prims <= config.effectiveLeafCap() && asLeaf <= asInner);
    tree.prims[node] = prims;
    tree.leaf[node] = leaf;
    tree.cost[node] = leaf ? asLeaf : asInner;
    tree.height[node] = leaf ? 0 : 1 + std::max(tree.height[l], tree.height[r]);
}

namespace {

using Nodes = std::vector<BvhNode, TraversalAllocator<BvhNode>>;

// Subtrees over fewer primitives than this are emitted as parallel jobs and appended in order,
// as bvh_builder's top-down jobs.
constexpr uint32_t kJobPrimitives = 4096;

// A subtree left to a job: its cluster, its slot in the nodes above, its depth, and where its
// primitives start in `ordered` (known from the primitive counts).
struct EmitJob {
    uint32_t cluster;
    uint32_t slot;
    int depth;
    uint32_t first;
};

class Emitter {
public:
    Emitter(const ClusterTree& tree, std::span<const PrimRef> leafRefs, const BuildConfig& config,
            std::span<PrimRef> ordered)
        : tree_(tree), leafRefs_(leafRefs), config_(config), ordered_(ordered) {}

    // The nodes of the subtree at `job` (root at 0, padding slot, pairs), depth first; with
    // `deferred`, subtrees below kJobPrimitives are left to jobs appended there.
    Nodes emit(const EmitJob& job, std::vector<EmitJob>* deferred) {
        constexpr int kRebuildDepth = kBvhMaxDepth / 2;
        const uint32_t n = tree_.leafCount;
        Nodes nodes;
        nodes.reserve(2 * size_t(tree_.prims[job.cluster]));
        nodes.resize(2);
        nodes[1] = BvhNode{{0, 0, 0, 0, 0, 0}, 0, 0};
        written_ = job.first;
        std::vector<EmitJob> stack{{job.cluster, 0, job.depth, 0}};
        while (!stack.empty()) {
            const EmitJob item = stack.back();
            stack.pop_back();
            const uint32_t c = item.cluster;
            if (deferred && item.slot != 0 && tree_.prims[c] < kJobPrimitives) {
                deferred->push_back({c, item.slot, item.depth, written_});
                written_ += tree_.prims[c];
                continue;
            }
            if (item.depth == kRebuildDepth && item.depth + tree_.height[c] >= uint32_t(kBvhMaxDepth)) {
                rebuild(c, item, nodes);
                continue;
            }
            BvhNode& node = nodes[item.slot];
            node.setBox(tree_.boxes[c].bounds());
            if (tree_.leaf[c]) {
                node.index = written_;
                node.count = tree_.prims[c];
                gather(c);
                continue;
            }
            const uint32_t left = uint32_t(nodes.size());
            node.index = left;  // `node` stays valid: reserve() covers every node there can be
            node.count = 0;
            nodes.emplace_back();
            nodes.emplace_back();
            stack.push_back({tree_.children[2 * size_t(c - n) + 1], left + 1, item.depth + 1, 0});
            stack.push_back({tree_.children[2 * size_t(c - n)], left, item.depth + 1, 0});
        }
        return nodes;
    }

private:
    // Writes the primitives below `node` to `ordered`, left to right.
    void gather(uint32_t node) {
        const uint32_t n = tree_.leafCount;
        below_.assign(1, node);
        while (!below_.empty()) {
            const uint32_t c = below_.back();
            below_.pop_back();
            if (c < n) {
                ordered_[written_++] = leafRefs_[c];
                continue;
            }
            below_.push_back(tree_.children[2 * size_t(c - n) + 1]);
            below_.push_back(tree_.children[2 * size_t(c - n)]);
        }
    }

    // The subtree at `c` built again by binned SAH, whose median rule keeps it within the
    // depth bound from kRebuildDepth on.
    void rebuild(uint32_t c, const EmitJob& item, Nodes& nodes) {
        const uint32_t first = written_;
        gather(c);
        BoundsAccumulator<simd::Scalar<4>> acc;
        for (uint32_t i = first; i < written_; ++i) acc.add(ordered_[i]);
        const Nodes subtree = BinnedSahBuilder(config_, BinnedSahConfig{})
                                  .build(ordered_, {first, written_, acc.bounds(), acc.centroidBounds()}, item.depth);
        appendSubtree(nodes, item.slot, subtree);
    }

    const ClusterTree& tree_;
    std::span<const PrimRef> leafRefs_;
    const BuildConfig& config_;
    std::span<PrimRef> ordered_;
    uint32_t written_ = 0;
    std::vector<uint32_t> below_;  // the gather's stack
};

}  // namespace

Nodes bvhNodesFromClusterTree(const ClusterTree& tree, std::span<const PrimRef> leafRefs, const BuildConfig& config,
                              std::span<PrimRef> ordered) {
    std::vector<EmitJob> jobs;
    Nodes nodes = Emitter(tree, leafRefs, config, ordered).emit({tree.root(), 0, 0, 0}, &jobs);
    std::vector<Nodes> subtrees(jobs.size());
    onThreads(config.threads, [&] {
        tbb::parallel_for(size_t(0), jobs.size(), [&](size_t j) {
            subtrees[j] = Emitter(tree, leafRefs, config, ordered).emit(jobs[j], nullptr);
        });
    });
    for (size_t j = 0; j < jobs.size(); ++j) appendSubtree(nodes, jobs[j].slot, subtrees[j]);
    return nodes;
}

}  // namespace bvhlab
