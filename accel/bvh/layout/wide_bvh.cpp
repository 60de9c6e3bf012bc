#include "accel/bvh/layout/wide_bvh.h"

#include <algorithm>
#include <memory>
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

// The dynamic programme of the collapse, per binary node n and lane budget i = 1..N.
template <int N>
class CollapsePlan {
public:
    CollapsePlan(const std::vector<BvhNode, TraversalAllocator<BvhNode>>& binary, const CollapseCosts& costs)
        : binary_(binary), plan_(new Choice[binary.size()]) {
        // Children come after their parent (depth-first order, bvh.h): bottom up is backwards.
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
        const float leaf = c.triangles <= costs.leafCap ? costs.cIntersect * area * float(blocksFor(c.triangles))
                                                        : kInfinity;
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

}  // namespace

template <int N>
WideBvh<N> collapseToWide(Bvh&& bvh, const CollapseCosts& costs) {
    WideBvh<N> wide;
    if (bvh.empty()) return wide;
    const std::vector<BvhNode, TraversalAllocator<BvhNode>>& binary = bvh.nodes;
    const CollapsePlan<N> plan(binary, costs);
    wide.nodes.reserve(binary.size() / 2 + 1);
    size_t blocks = 0;  // merging leaves only saves blocks: an upper bound
    for (const BvhNode& n : binary) blocks += n.isLeaf() ? blocksFor(n.count) : 0;
    wide.blocks.reserve(blocks);
    wide.primIndices.reserve(blocks * TriangleBlock::kLanes);

    // A leaf lane: the triangles of the binary leaves below n, left to right (a binary leaf's
    // straight from its arrays: most leaf lanes are one).
    std::vector<Triangle> triangles;
    std::vector<uint32_t> prims, below;
    const auto appendLeaf = [&](uint32_t n) {
        const BvhNode& leaf = binary[n];
        if (leaf.isLeaf())
            return wide.appendLeaf(&bvh.leafTriangles[leaf.index], &bvh.primIndices[leaf.index], leaf.count);
        triangles.clear(), prims.clear();
        below.assign(1, n);
        while (!below.empty()) {
            const BvhNode& node = binary[below.back()];
            below.pop_back();
            if (node.isLeaf()) {
                const Triangle* t = &bvh.leafTriangles[node.index];
                const uint32_t* p = &bvh.primIndices[node.index];
                triangles.insert(triangles.end(), t, t + node.count);
                prims.insert(prims.end(), p, p + node.count);
            } else {
                below.push_back(node.index + 1);
                below.push_back(node.index);
            }
        }
        return wide.appendLeaf(triangles.data(), prims.data(), uint32_t(prims.size()));
    };

    // Work: an inner binary node whose lanes fill the wide node at `slot`.
    struct Work {
        uint32_t binary;
        uint32_t slot;
    };
    std::vector<Work> stack;
    wide.nodes.push_back(emptyWideNode<N>());
    if (plan.rootIsOneLeaf()) {
        WideNode<N>& root = wide.nodes[0];
        const Bounds3 b = binary[0].box();
        for (int a = 0; a < 3; ++a) root.lower[a][0] = b.lower[a], root.upper[a][0] = b.upper[a];
        root.child[0] = appendLeaf(0);
        root.count[0] = plan.triangles(0);
    } else {
        stack.push_back({0, 0});
    }
    while (!stack.empty()) {
        const Work work = stack.back();
        stack.pop_back();
        uint32_t lanes[N];
        const int n = plan.lanesOf(work.binary, lanes);
        WideNode<N> node = emptyWideNode<N>();
        for (int i = 0; i < n; ++i) {
            const Bounds3 b = binary[lanes[i]].box();
            for (int a = 0; a < 3; ++a) node.lower[a][i] = b.lower[a], node.upper[a][i] = b.upper[a];
            if (plan.asLeaf(lanes[i])) node.child[i] = appendLeaf(lanes[i]), node.count[i] = plan.triangles(lanes[i]);
        }
        // Inner lanes (count 0) get wide nodes of their own, in lane order.
        for (int i = 0; i < n; ++i) {
            if (node.count[i] != 0) continue;
            node.child[i] = uint32_t(wide.nodes.size());
            wide.nodes.push_back(emptyWideNode<N>());
            stack.push_back({lanes[i], node.child[i]});
        }
        wide.nodes[work.slot] = node;
    }
    bvh = Bvh();
    return wide;
}

template WideBvh<4> collapseToWide<4>(Bvh&&, const CollapseCosts&);
template WideBvh<8> collapseToWide<8>(Bvh&&, const CollapseCosts&);

}  // namespace bvhlab
