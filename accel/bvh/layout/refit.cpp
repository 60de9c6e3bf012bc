#include "accel/bvh/layout/refit.h"

#include <tbb/parallel_invoke.h>
#include <tbb/task_group.h>

#include <algorithm>

namespace bvhlab {

namespace {

// Subtrees above this depth are refitted as tasks: up to 2^10 of a binary tree (a wide one's
// bound is below), many more than threads, each large enough to outweigh its scheduling.
constexpr int kBinaryTaskLevels = 10;

// The binary refit of node n and its subtree; `leaf(first, count)` refreshes a leaf's copies
// and returns their box.
template <typename Leaf>
Bounds3 refitBinaryNode(BvhNode* nodes, uint32_t n, int depth, const Leaf& leaf) {
    BvhNode& node = nodes[n];
    Bounds3 box;
    if (node.isLeaf()) {
        box = leaf(node.index, node.count);
    } else {
        Bounds3 left, right;
        if (depth < kBinaryTaskLevels) {
            tbb::parallel_invoke([&] { left = refitBinaryNode(nodes, node.index, depth + 1, leaf); },
                                 [&] { right = refitBinaryNode(nodes, node.index + 1, depth + 1, leaf); });
        } else {
            left = refitBinaryNode(nodes, node.index, depth + 1, leaf);
            right = refitBinaryNode(nodes, node.index + 1, depth + 1, leaf);
        }
        box = unionOf(left, right);
    }
    node.setBox(box);
    return box;
}

template <typename Leaf>
void refitBinaryTree(std::vector<BvhNode, TraversalAllocator<BvhNode>>& nodes, const Leaf& leaf) {
    if (!nodes.empty()) refitBinaryNode(nodes.data(), 0, 0, leaf);
}

// The box of a triangle's three vertices, into lower and upper per axis.
inline void extendBy(const Triangle& t, float (&lower)[3], float (&upper)[3]) {
    for (int a = 0; a < 3; ++a) {
        lower[a] = std::min(std::min(lower[a], t.v0[a]), std::min(t.v1[a], t.v2[a]));
        upper[a] = std::max(std::max(upper[a], t.v0[a]), std::max(t.v1[a], t.v2[a]));
    }
}

inline Bounds3 boxOf(const float (&lower)[3], const float (&upper)[3]) {
    return {{lower[0], lower[1], lower[2]}, {upper[0], upper[1], upper[2]}};
}

// Levels of a wide tree whose nodes run their inner lanes as tasks: N^levels subtrees, about
// as many as kBinaryTaskLevels gives a binary tree.
template <int N>
constexpr int kWideTaskLevels = N == 4 ? 5 : 4;

template <int N>
class WideRefit {
public:
    WideRefit(WideBvh<N>& bvh, const PrimitiveSet& prims) : bvh_(bvh), triangles_(prims.triangles.data()) {}

    // Refits node n and its subtree; returns the node's box (its lanes' union).
    Bounds3 node(uint32_t n, int depth) {
        WideNode<N>& node = bvh_.nodes[n];
        Bounds3 lanes[N];
        if (depth < kWideTaskLevels<N>) {
            tbb::task_group tasks;
            for (int i = 0; i < N; ++i)
                if (node.child[i] != 0 && !wide_child::isLeaf(node.child[i]))
                    tasks.run(
                        [this, &lanes, i, child = node.child[i], depth] { lanes[i] = this->node(child, depth + 1); });
            for (int i = 0; i < N; ++i)
                if (wide_child::isLeaf(node.child[i])) lanes[i] = leaf(node.child[i]);
            tasks.wait();
        } else {
            for (int i = 0; i < N; ++i) {
                const uint32_t child = node.child[i];
                if (child == 0) continue;  // an empty lane (the root is no node's child)
                lanes[i] = wide_child::isLeaf(child) ? leaf(child) : this->node(child, depth + 1);
            }
        }
        Bounds3 box;
        for (int i = 0; i < N; ++i) {
            if (node.child[i] == 0) continue;
            for (int a = 0; a < 3; ++a) node.lower[a][i] = lanes[i].lower[a], node.upper[a][i] = lanes[i].upper[a];
            box = unionOf(box, lanes[i]);
        }
        orderChildren(node);
        return box;
    }

private:
    // A leaf lane's blocks read again: each real lane's triangle, padding repeating the last.
    Bounds3 leaf(uint32_t child) {
        float lower[3] = {kInfinity, kInfinity, kInfinity}, upper[3] = {-kInfinity, -kInfinity, -kInfinity};
        const uint32_t first = wide_child::firstBlock(child), end = first + wide_child::blocks(child);
        const uint32_t* prim = &bvh_.primIndices[size_t(first) * TriangleBlock::kLanes];
        const Triangle* last = nullptr;
        for (uint32_t b = first; b < end; ++b) {
            TriangleBlock& block = bvh_.blocks[b];
            for (int lane = 0; lane < TriangleBlock::kLanes; ++lane, ++prim) {
                if (*prim != kInvalidPrimitive) {
                    last = &triangles_[*prim];
                    extendBy(*last, lower, upper);
                }
                block.set(lane, *last);
            }
        }
        return boxOf(lower, upper);
    }

    WideBvh<N>& bvh_;
    const Triangle* triangles_;
};

}  // namespace

void refitBinary(BinaryBvh& bvh, const PrimitiveSet& prims) {
    bvh.leafTriangles.resize(bvh.primIndices.size());
    const uint32_t* primIndices = bvh.primIndices.data();
    Triangle* leafTriangles = bvh.leafTriangles.data();
    const Triangle* triangles = prims.triangles.data();
    refitBinaryTree(bvh.nodes, [=](uint32_t first, uint32_t count) {
        float lower[3] = {kInfinity, kInfinity, kInfinity}, upper[3] = {-kInfinity, -kInfinity, -kInfinity};
        for (uint32_t i = first, end = first + count; i < end; ++i) {
            const Triangle& t = triangles[primIndices[i]];
            leafTriangles[i] = t;
            extendBy(t, lower, upper);
        }
        return boxOf(lower, upper);
    });
}

void refitQuadrics(QuadricBvh& bvh, const PrimitiveSet& prims) {
    refitBinaryTree(bvh.nodes, [&](uint32_t first, uint32_t count) {
        Bounds3 box;
        for (uint32_t i = first, end = first + count; i < end; ++i) {
            bvh.leafShapes[i] = prims.quadric(bvh.primIndices[i]);
            box.extend(boundsOf(bvh.leafShapes[i]));
        }
        return box;
    });
}

template <int N>
void refitWide(WideBvh<N>& bvh, const PrimitiveSet& prims) {
    if (!bvh.empty()) WideRefit<N>(bvh, prims).node(0, 0);
}

template void refitWide<4>(WideBvh<4>&, const PrimitiveSet&);
template void refitWide<8>(WideBvh<8>&, const PrimitiveSet&);

}  // namespace bvhlab
