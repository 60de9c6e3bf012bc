#include "accel/bvh/build/cluster_tree.h"

#include "accel/bvh/build/build_threads.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace bvhlab {

namespace {

// What the leaf-forming pass decides per node, bottom-up.
struct LeafForming {
    std::vector<uint32_t> prims;   // primitives below the node
    std::vector<uint32_t> height;  // of the node's subtree once leaves are formed (0: a leaf)
    std::vector<float> cost;       // SAH cost of that subtree, unnormalised (areas, not ratios)
    std::vector<uint8_t> leaf;     // 1: the node becomes a leaf of all its primitives
};

float halfArea(const ClusterBox& b) {
    const float dx = b.upper[0] - b.lower[0], dy = b.upper[1] - b.lower[1], dz = b.upper[2] - b.lower[2];
    return dx * dy + dy * dz + dz * dx;
}

// Each node's cheapest form: a leaf (C_isect * tests * A) or an inner node (C_trav * A + its
// children's costs), as the top-down SAH builders decide but with the children's whole
// subtrees known. Nodes of one merge iteration are independent: one parallel loop each.
LeafForming formLeaves(const ClusterTree& tree, const BvhBuildConfig& config) {
    const size_t nodes = tree.boxes.size();
    const uint32_t n = tree.leafCount;
    LeafForming f{std::vector<uint32_t>(nodes), std::vector<uint32_t>(nodes), std::vector<float>(nodes),
                  std::vector<uint8_t>(nodes)};
    const uint32_t leafCap = config.effectiveLeafCap();
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 1 << 14), [&](const tbb::blocked_range<uint32_t>& r) {
        for (uint32_t i = r.begin(); i < r.end(); ++i) {
            f.prims[i] = 1, f.height[i] = 0, f.leaf[i] = 1;
            f.cost[i] = config.cIntersect * float(config.sahTests(1)) * halfArea(tree.boxes[i]);
        }
    });
    uint32_t begin = n;
    for (const uint32_t end : tree.mergeEnds) {
        tbb::parallel_for(tbb::blocked_range<uint32_t>(begin, end, 1 << 12), [&](const tbb::blocked_range<uint32_t>& r) {
            for (uint32_t i = r.begin(); i < r.end(); ++i) {
                const uint32_t l = tree.children[2 * size_t(i - n)], rt = tree.children[2 * size_t(i - n) + 1];
                const uint32_t prims = f.prims[l] + f.prims[rt];
                const float area = halfArea(tree.boxes[i]);
                const float asInner = config.cTraversal * area + f.cost[l] + f.cost[rt];
                const float asLeaf = config.cIntersect * float(config.sahTests(prims)) * area;
                const bool leaf = prims <= uint32_t(config.maxLeaf) ||
                                  (config.sahTermination && prims <= leafCap && asLeaf <= asInner);
                f.prims[i] = prims;
                f.leaf[i] = leaf;
                f.cost[i] = leaf ? asLeaf : asInner;
                f.height[i] = leaf ? 0 : 1 + std::max(f.height[l], f.height[rt]);
            }
        });
        begin = end;
    }
    return f;
}

}  // namespace

std::vector<BvhNode, TraversalAllocator<BvhNode>> bvhNodesFromClusterTree(const ClusterTree& tree,
                                                                          std::span<const PrimRef> leafRefs,
                                                                          const BvhBuildConfig& config,
                                                                          std::span<PrimRef> ordered) {
    LeafForming f;
    onThreads(config.threads, [&] { f = formLeaves(tree, config); });
    const uint32_t n = tree.leafCount;
    constexpr int kRebuildDepth = kBvhMaxDepth / 2;

    std::vector<BvhNode, TraversalAllocator<BvhNode>> nodes;
    nodes.reserve(2 * size_t(n));
    nodes.resize(2);
    nodes[1] = BvhNode{{0, 0, 0, 0, 0, 0}, 0, 0};
    uint32_t written = 0;  // PrimRefs written to `ordered`
    std::vector<uint32_t> below;  // the gather's stack
    // Writes the primitives below `node` to `ordered`, left to right.
    const auto gather = [&](uint32_t node) {
        below.assign(1, node);
        while (!below.empty()) {
            const uint32_t c = below.back();
            below.pop_back();
            if (c < n) {
                ordered[written++] = leafRefs[c];
                continue;
            }
            below.push_back(tree.children[2 * size_t(c - n) + 1]);
            below.push_back(tree.children[2 * size_t(c - n)]);
        }
    };

    struct WorkItem {
        uint32_t cluster;
        uint32_t slot;
        int depth;
    };
    std::vector<WorkItem> stack{{tree.root(), 0, 0}};
    while (!stack.empty()) {
        const WorkItem item = stack.back();
        stack.pop_back();
        const uint32_t c = item.cluster;
        if (item.depth == kRebuildDepth && item.depth + f.height[c] >= uint32_t(kBvhMaxDepth)) {
            const uint32_t first = written;
            gather(c);
            BoundsAccumulator<simd::Scalar<4>> acc;
            for (uint32_t i = first; i < written; ++i) acc.add(ordered[i]);
            const auto subtree = makeBvhBuilder(BvhKind::BinnedSah, config)
                                     ->build(ordered, {first, written, acc.bounds(), acc.centroidBounds()}, item.depth);
            appendSubtree(nodes, item.slot, subtree);
            continue;
        }
        BvhNode& node = nodes[item.slot];
        node.setBox(tree.boxes[c].bounds());
        if (f.leaf[c]) {
            node.index = written;
            node.count = f.prims[c];
            gather(c);
            continue;
        }
        const uint32_t left = uint32_t(nodes.size());
        node.index = left;  // `node` stays valid: reserve() covers every node there can be
        node.count = 0;
        nodes.emplace_back();
        nodes.emplace_back();
        stack.push_back({tree.children[2 * size_t(c - n) + 1], left + 1, item.depth + 1});
        stack.push_back({tree.children[2 * size_t(c - n)], left, item.depth + 1});
    }
    return nodes;
}

}  // namespace bvhlab
