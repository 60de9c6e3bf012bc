#include "accel/bvh/layout/wide_bvh.h"

#include <algorithm>
#include <utility>

namespace bvhlab {

namespace {

template <int N>
WideNode<N> emptyWideNode() {
    WideNode<N> n;
    for (int a = 0; a < 3; ++a) {
        std::fill_n(n.lower[a], N, kInfinity);
        std::fill_n(n.upper[a], N, -kInfinity);
    }
    std::fill_n(n.child, N, 0u);
    std::fill_n(n.count, N, 0u);
    return n;
}

}  // namespace

template <int N>
WideBvh<N> collapseToWide(Bvh&& bvh) {
    WideBvh<N> wide;
    if (bvh.empty()) return wide;
    const std::vector<BvhNode, TraversalAllocator<BvhNode>>& binary = bvh.nodes;
    wide.nodes.reserve(binary.size() / 2 + 1);
    size_t blocks = 0;
    for (const BvhNode& n : binary) blocks += n.isLeaf() ? blocksFor(n.count) : 0;
    wide.blocks.reserve(blocks);
    wide.primIndices.reserve(blocks * TriangleBlock::kLanes);
    const auto appendLeaf = [&](const BvhNode& leaf) {
        return wide.appendLeaf(&bvh.leafTriangles[leaf.index], &bvh.primIndices[leaf.index], leaf.count);
    };

    // Work: a binary node whose children fill the wide node at `slot`.
    struct Work {
        uint32_t binary;
        uint32_t slot;
    };
    std::vector<Work> stack;
    wide.nodes.push_back(emptyWideNode<N>());
    if (binary[0].isLeaf()) {
        WideNode<N>& root = wide.nodes[0];
        const Bounds3 b = binary[0].box();
        for (int a = 0; a < 3; ++a) root.lower[a][0] = b.lower[a], root.upper[a][0] = b.upper[a];
        root.child[0] = appendLeaf(binary[0]);
        root.count[0] = binary[0].count;
        bvh = Bvh();
        return wide;
    }
    stack.push_back({0, 0});
    while (!stack.empty()) {
        const Work work = stack.back();
        stack.pop_back();
        // The children to gather: start with the binary node's two, open the largest inner one
        // until there are N or only leaves remain.
        uint32_t children[N] = {binary[work.binary].index, binary[work.binary].index + 1};
        int n = 2;
        while (n < N) {
            int open = -1;
            float largest = -1.0f;
            for (int i = 0; i < n; ++i) {
                const BvhNode& c = binary[children[i]];
                const float area = c.box().halfArea();
                if (!c.isLeaf() && area > largest) open = i, largest = area;
            }
            if (open < 0) break;
            const uint32_t first = binary[children[open]].index;
            children[open] = first;
            children[n++] = first + 1;
        }
        WideNode<N> node = emptyWideNode<N>();
        for (int i = 0; i < n; ++i) {
            const BvhNode& c = binary[children[i]];
            const Bounds3 b = c.box();
            for (int a = 0; a < 3; ++a) node.lower[a][i] = b.lower[a], node.upper[a][i] = b.upper[a];
            if (c.isLeaf()) node.child[i] = appendLeaf(c), node.count[i] = c.count;
        }
        // Inner children (count 0) get wide nodes of their own, in lane order.
        for (int i = 0; i < n; ++i) {
            if (node.count[i] != 0) continue;
            node.child[i] = uint32_t(wide.nodes.size());
            wide.nodes.push_back(emptyWideNode<N>());
            stack.push_back({children[i], node.child[i]});
        }
        wide.nodes[work.slot] = node;
    }
    bvh = Bvh();
    return wide;
}

template WideBvh<4> collapseToWide<4>(Bvh&&);
template WideBvh<8> collapseToWide<8>(Bvh&&);

}  // namespace bvhlab
