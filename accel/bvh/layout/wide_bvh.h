// An N-wide BVH collapsed from a finished binary one (as Embree's BVH4 and BVH8): each node
// holds the boxes of up to N children in SoA order, so that one SIMD test checks all of them,
// and a ray takes fewer, wider steps. A leaf of the wide tree holds the triangles of a binary
// subtree (one binary leaf, or small ones merged), stored in SIMD blocks (triangle_blocks.h).
// sahbvh4 is N = 4, sahbvh8 N = 8.
#pragma once

#include "accel/bvh/layout/binary_bvh.h"
#include "accel/bvh/layout/triangle_blocks.h"

#include <cmath>
#include <cstdint>

namespace bvhlab {

// A wide node's reference to one child, one 32-bit word: an inner child's node index, or, with
// kLeaf set, a leaf's first TriangleBlock and its number of blocks. The traversal learns from the
// word alone what to read next, and how much.
namespace wide_child {
inline constexpr uint32_t kLeaf = 1u << 31;
inline constexpr int kFirstBlockBits = 26;  // up to 2^26 blocks (2^29 triangles)
inline constexpr uint32_t kMaxBlocks = 32;  // BVH::leafCap's 256 triangles at most
constexpr uint32_t inner(uint32_t node) { return node; }
constexpr uint32_t leaf(uint32_t firstBlock, uint32_t blocks) {
    return kLeaf | (blocks - 1) << kFirstBlockBits | firstBlock;
}
constexpr bool isLeaf(uint32_t child) { return (child & kLeaf) != 0; }
constexpr uint32_t firstBlock(uint32_t child) { return child & ((1u << kFirstBlockBits) - 1); }
constexpr uint32_t blocks(uint32_t child) { return ((child & ~kLeaf) >> kFirstBlockBits) + 1; }
}  // namespace wide_child

template <int N>
struct alignas(64) WideNode {
    static constexpr int kWidth = N;
    // Per axis, the N children's bounds; an empty lane has lower = +inf and upper = -inf,
    // which no ray overlaps (its slab distances are +inf in and -inf out, never NaN). Its child
    // word is 0.
    float lower[3][N];
    float upper[3][N];
    uint32_t child[N];  // wide_child words
    // The children in the order a ray of each direction octant reaches them, far to near
    // (Fuetterling et al. 2017, as tinybvh's BVH8_CPU): bits [3o, 3o + 3) of order[p] are the
    // lane at position p for octant o (bit 0 of o: x < 0, bit 1: y < 0, bit 2: z < 0).
    // Positions are sorted by where each child's box begins along the octant's diagonal, so the
    // traversal orders the children it hits with one permutation instead of sorting distances.
    uint32_t order[N];
};
static_assert(sizeof(WideNode<4>) == 128, "a 4-wide node fills two cache lines");
static_assert(sizeof(WideNode<8>) == 256, "an 8-wide node fills four cache lines");

// The octant of a direction, as WideNode::order numbers them.
inline int directionOctant(const Vec3& dir) {
    return (std::signbit(dir.x) ? 1 : 0) | (std::signbit(dir.y) ? 2 : 0) | (std::signbit(dir.z) ? 4 : 0);
}

// Fills node.order from the node's boxes: per octant, the lanes far to near by where each box
// begins along the octant's diagonal (the corner a ray of that octant reaches first), ties in
// lane order; empty lanes farthest. Instantiated for N = 4 and 8.
template <int N>
void orderChildren(WideNode<N>& node);

// Root at 0. Empty when there is nothing to build over.
template <int N>
using WideBvh = NodeTree<WideNode<N>, TriangleBlockLeaves>;

// What the collapse charges, in the build's SAH units: a wide node visited, a block of
// triangles tested; and the largest leaf it may merge (the build's leaf cap).
struct CollapseCosts {
    float cTraversal;
    float cIntersect;
    uint32_t leafCap;
};

// Collapses `bvh` (left as it is: BvhAccelerator keeps it for its statistics) by SAH, after Ylitie, Karras and Laine
// 2017 ("Efficient incoherent ray traversal on GPUs through compressed wide BVHs", section 4.1): bottom up, each binary
// node's subtree gets its cheapest form as at most 1..N lanes of a wide node, where one lane is
// the node itself, either a leaf of all its triangles (at most leafCap, charged by blocks) or a
// wide node whose lanes are drawn from its subtree. Small sibling leaves thus merge when fewer
// blocks pay, and a wide node opens the descendants that pay, not the largest box. Every lane
// is a proper descendant of its node's binary node, so the wide tree is no deeper than the
// binary one; a merged leaf lists its binary leaves' triangles left to right. The root is a
// wide node (holding a single leaf lane when all triangles are cheapest as one leaf). Large
// subtrees are written as TBB tasks (in the caller's arena), each at a place fixed beforehand:
// the layout does not depend on the thread count. Instantiated for N = 4 and 8.
template <int N>
WideBvh<N> collapseToWide(const BinaryBvh& bvh, const CollapseCosts& costs);

}  // namespace bvhlab
