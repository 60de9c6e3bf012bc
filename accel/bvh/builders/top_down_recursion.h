// The recursion every top-down BVH build shares (BvhSplitRule's in-place ranges, sbvh's
// growing reference vectors): a work stack, depth first and left before right, so that a
// subtree's nodes are contiguous and the stack holds at most one pending right sibling per
// level; the root at 0, a padding slot, then sibling pairs. The build decides the rest:
//   defer(range, node, depth) -> bool: true when the range is left to a later job (its node
//     slot stays for the caller to fill; the range may be moved from);
//   chooseSplit(range, depth) -> an optional with .left and .right ranges; nullopt: a leaf;
//   makeLeaf(range, node): sets the leaf's index and count.
#pragma once

#include "accel/bvh/builders/build_jobs.h"

#include <fmt/core.h>

#include <cassert>
#include <stdexcept>
#include <vector>

namespace bvhlab {

template <typename Range, typename Defer, typename ChooseSplit, typename MakeLeaf>
BvhNodes buildTopDown(Range root, int depth, size_t maxNodes, Defer defer, ChooseSplit chooseSplit, MakeLeaf makeLeaf) {
    BvhNodes nodes;
    if (root.size() == 0) return nodes;
    nodes.reserve(maxNodes);
    nodes.resize(2);
    nodes[1] = BvhNode{{0, 0, 0, 0, 0, 0}, 0, 0};

    struct WorkItem {
        Range range;
        uint32_t node;
        int depth;
    };
    std::vector<WorkItem> stack;
    stack.reserve(2 * kBvhMaxDepth);
    stack.push_back({std::move(root), 0, depth});
    while (!stack.empty()) {
        WorkItem item = std::move(stack.back());
        stack.pop_back();
        if (defer(item.range, item.node, item.depth)) continue;
        nodes[item.node].setBox(item.range.bounds);
        auto split = chooseSplit(item.range, item.depth);
        if (!split) {
            assert(item.range.size() > 0);  // an empty leaf would read as an inner node (count == 0)
            makeLeaf(item.range, nodes[item.node]);
            continue;
        }
        // A split rule's contract: two non-empty halves (an empty leaf would read as an inner
        // node, count == 0), and a depth the traversal stacks can hold (kBvhMaxDepth).
        if (split->left.size() == 0 || split->right.size() == 0 || item.depth + 1 >= kBvhMaxDepth)
            throw std::logic_error(fmt::format("BVH builder: split of {} primitives at depth {} into {} + {}",
                                               item.range.size(), item.depth, split->left.size(), split->right.size()));
        const uint32_t left = uint32_t(nodes.size());
        nodes[item.node].index = left;
        nodes[item.node].count = 0;
        nodes.emplace_back();
        nodes.emplace_back();
        stack.push_back({std::move(split->right), left + 1, item.depth + 1});
        stack.push_back({std::move(split->left), left, item.depth + 1});
    }
    return nodes;
}

}  // namespace bvhlab
