#include "accel/bvh/layout/wide_bvh.h"

#include <fmt/format.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

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
    std::fill_n(n.order, N, 0u);
    return n;
}

// A leaf's child word; throws when the layout cannot address it.
uint32_t leafChild(uint32_t firstBlock, uint32_t triangles) {
    const uint32_t blocks = blocksFor(triangles);
    if (blocks > wide_child::kMaxBlocks || firstBlock + blocks > (1u << wide_child::kFirstBlockBits))
        throw std::length_error(fmt::format(
            "the wide BVH addresses {} blocks of at most {} in a leaf; this one needs "
            "blocks {} to {}",
            1u << wide_child::kFirstBlockBits, wide_child::kMaxBlocks, firstBlock, firstBlock + blocks - 1));
    return wide_child::leaf(firstBlock, blocks);
}

// The dynamic programme of the collapse, per binary node n and lane budget i = 1..N.
template <int N>
class CollapsePlan {
public:
    CollapsePlan(const std::vector<BvhNode, TraversalAllocator<BvhNode>>& binary, const CollapseCosts& costs)
        : binary_(binary), plan_(new Choice[binary.size()]) {
        // Children come after their parent (depth-first order, binary_bvh.h): bottom up is backwards.
        for (size_t n = binary.size(); n-- > 0;) {
            if (n != 1) plan(uint32_t(n), costs);
        }
    }

    uint32_t triangles(uint32_t n) const { return plan_[n].triangles; }
    bool asLeaf(uint32_t n) const { return plan_[n].asLeaf; }
    // The root: one leaf lane when that is cheapest; otherwise a wide node.
    bool rootIsOneLeaf() const { return plan_[0].spread[N - 1] == 1 && plan_[0].asLeaf; }

    // The lanes of the wide node made of inner binary node n: the cheapest forest of at most N
    // below it, left to right. Returns their number.
    int lanesOf(uint32_t n, uint32_t (&lanes)[N]) const {
        int count = 0;
        split(n, N, lanes, count);
        return count;
    }

private:
    // What the programme chose for one binary node n.
    struct Choice {
        float cost[N];       // [i - 1]: least SAH cost as at most i lanes
        uint8_t spread[N];   // [i - 1]: 1 = n is one lane; j = split into j between the children
        uint8_t left[N];     // [j - 1]: the left child's share of j lanes
        uint32_t triangles;  // below n
        bool asLeaf;         // n as one lane: a leaf (else a wide node)
    };

    void plan(uint32_t n, const CollapseCosts& costs) {
        const BvhNode& node = binary_[n];
        const float area = node.box().halfArea();
        Choice& c = plan_[n];
        if (node.isLeaf()) {
            c.triangles = node.count;
            c.asLeaf = true;
            std::fill_n(c.cost, N, costs.cIntersect * area * float(blocksFor(node.count)));
            std::fill_n(c.spread, N, uint8_t(1));
            return;
        }
        const Choice &l = plan_[node.index], &r = plan_[node.index + 1];
        c.triangles = l.triangles + r.triangles;
        // distribute[j - 1]: the cheapest j lanes or fewer split between the two children.
        float distribute[N];
        for (int j = 2; j <= N; ++j) {
            float best = l.cost[0] + r.cost[j - 2];
            c.left[j - 1] = 1;
            for (int k = 2; k < j; ++k) {
                const float split = l.cost[k - 1] + r.cost[j - k - 1];
                if (split < best) best = split, c.left[j - 1] = uint8_t(k);
            }
            distribute[j - 1] = best;
        }
        const float inner = costs.cTraversal * area + distribute[N - 1];
        const float leaf =
            c.triangles <= costs.leafCap ? costs.cIntersect * area * float(blocksFor(c.triangles)) : kInfinity;
        c.asLeaf = leaf <= inner;
        c.cost[0] = std::min(leaf, inner);
        c.spread[0] = 1;
        // On a tie, fewer lanes: they leave the parent room for others.
        for (int i = 2; i <= N; ++i) {
            const bool spreads = distribute[i - 1] < c.cost[i - 2];
            c.cost[i - 1] = spreads ? distribute[i - 1] : c.cost[i - 2];
            c.spread[i - 1] = spreads ? uint8_t(i) : c.spread[i - 2];
        }
    }

    // Appends the lanes of n's best forest of j >= 2 lanes split between its children.
    void split(uint32_t n, int j, uint32_t (&lanes)[N], int& count) const {
        const uint32_t l = binary_[n].index;
        const int k = plan_[n].left[j - 1];
        place(l, k, lanes, count);
        place(l + 1, j - k, lanes, count);
    }
    void place(uint32_t n, int i, uint32_t (&lanes)[N], int& count) const {
        const int s = plan_[n].spread[i - 1];
        if (s == 1) {
            lanes[count++] = n;
        } else {
            split(n, s, lanes, count);
        }
    }

    const std::vector<BvhNode, TraversalAllocator<BvhNode>>& binary_;
    // Per binary node; left uninitialised (no pass over them) until planned, the padding slot
    // never.
    std::unique_ptr<Choice[]> plan_;
};

// What the wide subtree of one wide node takes: the wide nodes below it and the blocks of all
// its leaves, its own leaf lanes included. Known before emission, they give every subtree its
// place in the arrays, so that subtrees are written in parallel into the layout the sequential
// depth-first emission makes.
struct SubtreeSize {
    uint32_t nodesBelow = 0;
    uint32_t blocks = 0;
};

// Subtrees of at least this many blocks are emitted as tasks of their own; smaller ones inline.
constexpr uint32_t kParallelBlocks = 512;

template <int N>
class WideEmitter {
public:
    WideEmitter(const BinaryBvh& bvh, const CollapsePlan<N>& plan, WideBvh<N>& wide)
        : bvh_(bvh), plan_(plan), wide_(wide), sizes_(new SubtreeSize[bvh.nodes.size()]) {}

    // The sizes of the wide subtree of inner binary node n and of every wide node below it.
    SubtreeSize measure(uint32_t n) {
        uint32_t lanes[N];
        const int count = plan_.lanesOf(n, lanes);
        SubtreeSize size;
        for (int i = 0; i < count; ++i) {
            if (plan_.asLeaf(lanes[i])) {
                size.blocks += blocksFor(plan_.triangles(lanes[i]));
            } else {
                const SubtreeSize below = measure(lanes[i]);
                size.nodesBelow += 1 + below.nodesBelow;
                size.blocks += below.blocks;
            }
        }
        return sizes_[n] = size;
    }

    // Writes the wide node of inner binary node n at `slot`, its leaves' blocks from block
    // `firstBlock` on (its own leaf lanes first, in lane order), its inner lanes' nodes at
    // `firstNode`, `firstNode` + 1, ... (lane order) and their subtrees after them, the last
    // lane's first: the order of a depth-first emission with a stack.
    void emit(uint32_t n, uint32_t slot, uint32_t firstNode, uint32_t firstBlock) {
        uint32_t lanes[N];
        const int count = plan_.lanesOf(n, lanes);
        WideNode<N> node = emptyWideNode<N>();
        uint32_t block = firstBlock, nextNode = firstNode;
        for (int i = 0; i < count; ++i) {
            const Bounds3 b = bvh_.nodes[lanes[i]].box();
            for (int a = 0; a < 3; ++a) node.lower[a][i] = b.lower[a], node.upper[a][i] = b.upper[a];
            if (plan_.asLeaf(lanes[i])) {
                const uint32_t triangles = plan_.triangles(lanes[i]);
                node.child[i] = leafChild(block, triangles);
                writeLeaf(lanes[i], block);
                block += blocksFor(triangles);
            }
        }
        for (int i = 0; i < count; ++i)
            if (!plan_.asLeaf(lanes[i])) node.child[i] = wide_child::inner(nextNode++);
        orderChildren(node);
        wide_.nodes[slot] = node;

        std::optional<tbb::task_group> tasks;  // made only where a subtree is large enough
        for (int i = count; i-- > 0;) {
            if (plan_.asLeaf(lanes[i])) continue;
            const SubtreeSize& size = sizes_[lanes[i]];
            const uint32_t child = lanes[i], childSlot = node.child[i], childNodes = nextNode, childBlocks = block;
            if (size.blocks >= kParallelBlocks) {
                if (!tasks) tasks.emplace();
                tasks->run([=, this] { emit(child, childSlot, childNodes, childBlocks); });
            } else {
                emit(child, childSlot, childNodes, childBlocks);
            }
            nextNode += size.nodesBelow, block += size.blocks;
        }
        if (tasks) tasks->wait();
    }

    // A leaf lane at `first`: the triangles of the binary leaves below n, left to right (a
    // binary leaf's straight from its arrays: most leaf lanes are one).
    void writeLeaf(uint32_t n, uint32_t first) {
        const BvhNode& leaf = bvh_.nodes[n];
        if (leaf.isLeaf()) {
            wide_.writeLeaf(first, &bvh_.leafTriangles[leaf.index], &bvh_.primIndices[leaf.index], leaf.count);
            return;
        }
        std::vector<Triangle> triangles;
        std::vector<uint32_t> prims, below(1, n);
        while (!below.empty()) {
            const BvhNode& node = bvh_.nodes[below.back()];
            below.pop_back();
            if (node.isLeaf()) {
                const Triangle* t = &bvh_.leafTriangles[node.index];
                const uint32_t* p = &bvh_.primIndices[node.index];
                triangles.insert(triangles.end(), t, t + node.count);
                prims.insert(prims.end(), p, p + node.count);
            } else {
                below.push_back(node.index + 1);
                below.push_back(node.index);
            }
        }
        wide_.writeLeaf(first, triangles.data(), prims.data(), uint32_t(prims.size()));
    }

private:
    const BinaryBvh& bvh_;
    const CollapsePlan<N>& plan_;
    WideBvh<N>& wide_;
    std::unique_ptr<SubtreeSize[]> sizes_;  // per inner binary node that becomes a wide node
};

}  // namespace

template <int N>
void orderChildren(WideNode<N>& node) {
    std::fill_n(node.order, N, 0u);
    for (int octant = 0; octant < 8; ++octant) {
        float begin[N];
        for (int i = 0; i < N; ++i) {
            begin[i] = kInfinity;
            if (!(node.lower[0][i] <= node.upper[0][i])) continue;  // empty
            begin[i] = 0.0f;
            for (int a = 0; a < 3; ++a) begin[i] += (octant >> a & 1) ? -node.upper[a][i] : node.lower[a][i];
        }
        // Far to near, ties in lane order: an insertion sort, stable, and without the buffer
        // std::stable_sort allocates (a refit orders every node again).
        int lanes[N];
        for (int i = 0; i < N; ++i) {
            int p = i;
            for (; p > 0 && begin[lanes[p - 1]] < begin[i]; --p) lanes[p] = lanes[p - 1];
            lanes[p] = i;
        }
        for (int p = 0; p < N; ++p) node.order[p] |= uint32_t(lanes[p]) << (3 * octant);
    }
}

template <int N>
WideBvh<N> collapseToWide(const BinaryBvh& bvh, const CollapseCosts& costs) {
    WideBvh<N> wide;
    if (bvh.empty()) return wide;
    const CollapsePlan<N> plan(bvh.nodes, costs);
    WideEmitter<N> emitter(bvh, plan, wide);
    if (plan.rootIsOneLeaf()) {
        const uint32_t triangles = plan.triangles(0);
        wide.resizeLeaves(blocksFor(triangles));
        WideNode<N> root = emptyWideNode<N>();
        const Bounds3 b = bvh.nodes[0].box();
        for (int a = 0; a < 3; ++a) root.lower[a][0] = b.lower[a], root.upper[a][0] = b.upper[a];
        root.child[0] = leafChild(0, triangles);
        orderChildren(root);
        emitter.writeLeaf(0, 0);
        wide.nodes.assign(1, root);
    } else {
        const SubtreeSize size = emitter.measure(0);
        wide.nodes.resize(1 + size.nodesBelow);
        wide.resizeLeaves(size.blocks);
        emitter.emit(0, 0, 1, 0);
    }
    return wide;
}

template void orderChildren<4>(WideNode<4>&);
template void orderChildren<8>(WideNode<8>&);
template WideBvh<4> collapseToWide<4>(const BinaryBvh&, const CollapseCosts&);
template WideBvh<8> collapseToWide<8>(const BinaryBvh&, const CollapseCosts&);

}  // namespace bvhlab
