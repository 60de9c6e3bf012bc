#include "accel/bvh/builders/insertion_optimizer.h"

#include <algorithm>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

namespace bvhlab {

namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// The tree with explicit parent links, so that a subtree can be cut out and put back anywhere.
// Node i is node i of the pair layout it was read from (slot 1 unused); removed inner nodes
// are reused as the parents that the reinsertions create, so no node is ever allocated.
struct LinkedTree {
    struct Node {
        Bounds3 box;
        float area = 0.0f;
        uint32_t parent = kNone;
        uint32_t child[2] = {kNone, kNone};  // kNone for a leaf
        uint32_t first = 0, count = 0;       // a leaf's range of the old leaf arrays
        int height = 0;                      // 0 for a leaf

        bool isLeaf() const { return child[0] == kNone; }
    };
    std::vector<Node> nodes;
    uint32_t root = 0;

    explicit LinkedTree(std::span<const BvhNode> layout);

    // The SAH's variable part: the leaves are fixed, so only the inner nodes' areas change.
    double innerArea() const;
    void replaceChild(uint32_t parent, uint32_t from, uint32_t to);
    // Boxes, areas and heights from `n` up to the root.
    void refit(uint32_t n);
    // Cuts inner node n and its parent out (n's sibling takes the parent's place), then
    // reinserts n's children, reusing n and its parent as their new parents.
    void reinsertChildrenOf(uint32_t n);
    void insert(uint32_t subtree, uint32_t freeNode);
    uint32_t bestSibling(uint32_t subtree) const;
};

LinkedTree::LinkedTree(std::span<const BvhNode> layout) : nodes(layout.size()) {
    std::vector<uint32_t> preorder{0};
    for (size_t i = 0; i < preorder.size(); ++i) {
        const uint32_t n = preorder[i];
        const BvhNode& node = layout[n];
        Node& linked = nodes[n];
        linked.box = node.box();
        linked.area = linked.box.halfArea();
        if (node.isLeaf()) {
            linked.first = node.index;
            linked.count = node.count;
            continue;
        }
        for (uint32_t c = 0; c < 2; ++c) {
            linked.child[c] = node.index + c;
            nodes[node.index + c].parent = n;
            preorder.push_back(node.index + c);
        }
    }
    for (size_t i = preorder.size(); i-- > 0;) {
        Node& node = nodes[preorder[i]];
        if (!node.isLeaf()) node.height = 1 + std::max(nodes[node.child[0]].height, nodes[node.child[1]].height);
    }
}

double LinkedTree::innerArea() const {
    double sum = 0.0;
    std::vector<uint32_t> stack{root};
    while (!stack.empty()) {
        const Node& node = nodes[stack.back()];
        stack.pop_back();
        if (node.isLeaf()) continue;
        sum += node.area;
        stack.push_back(node.child[0]);
        stack.push_back(node.child[1]);
    }
    return sum;
}

void LinkedTree::replaceChild(uint32_t parent, uint32_t from, uint32_t to) {
    nodes[to].parent = parent;
    if (parent == kNone) {
        root = to;
        return;
    }
    uint32_t* child = nodes[parent].child;
    child[child[0] == from ? 0 : 1] = to;
}

void LinkedTree::refit(uint32_t n) {
    for (; n != kNone; n = nodes[n].parent) {
        Node& node = nodes[n];
        const Node &left = nodes[node.child[0]], &right = nodes[node.child[1]];
        node.box = unionOf(left.box, right.box);
        node.area = node.box.halfArea();
        node.height = 1 + std::max(left.height, right.height);
    }
}

// Branch and bound over the tree, cheapest induced cost first (Bittner et al.'s search):
// putting `subtree` beside node x costs A(x u subtree) for the new parent plus the growth of
// every ancestor of x; below x the ancestors' growth only adds up, so a node whose induced cost
// plus A(subtree) cannot beat the best found ends the search. Positions that would take the
// tree to kBvhMaxDepth are skipped.
uint32_t LinkedTree::bestSibling(uint32_t subtree) const {
    struct Candidate {
        float induced;  // the growth of the node's ancestors
        uint32_t node;
        int depth;
        bool operator>(const Candidate& o) const {
            return induced > o.induced || (induced == o.induced && node > o.node);
        }
    };
    std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> queue;
    const Node& inserted = nodes[subtree];
    queue.push({0.0f, root, 0});
    float bestCost = std::numeric_limits<float>::infinity();
    uint32_t best = kNone;
    while (!queue.empty()) {
        const Candidate c = queue.top();
        queue.pop();
        if (c.induced + inserted.area >= bestCost) break;
        const Node& node = nodes[c.node];
        const float merged = unionOf(node.box, inserted.box).halfArea();
        const float cost = c.induced + merged;
        if (cost < bestCost && c.depth + 1 + std::max(node.height, inserted.height) < kBvhMaxDepth) {
            bestCost = cost;
            best = c.node;
        }
        const float induced = cost - node.area;
        if (node.isLeaf() || induced + inserted.area >= bestCost) continue;
        for (uint32_t child : node.child) queue.push({induced, child, c.depth + 1});
    }
    // No admissible position (only on a tree at the depth bound): beside the root; the pass
    // that made it is then undone for its depth.
    return best == kNone ? root : best;
}

void LinkedTree::insert(uint32_t subtree, uint32_t freeNode) {
    const uint32_t sibling = bestSibling(subtree);
    Node& parent = nodes[freeNode];
    replaceChild(nodes[sibling].parent, sibling, freeNode);
    parent.child[0] = sibling;
    parent.child[1] = subtree;
    nodes[sibling].parent = freeNode;
    nodes[subtree].parent = freeNode;
    refit(freeNode);
}

void LinkedTree::reinsertChildrenOf(uint32_t n) {
    const uint32_t parent = nodes[n].parent;
    const uint32_t* siblings = nodes[parent].child;
    const uint32_t sibling = siblings[0] == n ? siblings[1] : siblings[0];
    const uint32_t grandparent = nodes[parent].parent;
    replaceChild(grandparent, parent, sibling);
    if (grandparent != kNone) refit(grandparent);
    const uint32_t left = nodes[n].child[0], right = nodes[n].child[1];
    insert(left, n);
    insert(right, parent);
}

// How much area node n wastes: the product of the paper's three measures, A(n) (M_area),
// A(n) / min A(child) (M_min) and A(n) / mean A(child) (M_sum). Large nodes over small or
// far-apart children come first.
double inefficiency(const LinkedTree& tree, uint32_t n) {
    const LinkedTree::Node& node = tree.nodes[n];
    const double a = node.area;
    const double left = tree.nodes[node.child[0]].area, right = tree.nodes[node.child[1]].area;
    const double smallest = std::min(left, right), mean = 0.5 * (left + right);
    if (!(smallest > 0.0) || !(mean > 0.0)) return std::numeric_limits<double>::max();
    return a * (a / smallest) * (a / mean);
}

// One pass: every inner node but the root, most wasteful first (the order of the pass's
// start), has its children reinserted.
void optimizePass(LinkedTree& tree) {
    std::vector<std::pair<double, uint32_t>> order;
    for (uint32_t n = 0; n < tree.nodes.size(); ++n) {
        const LinkedTree::Node& node = tree.nodes[n];
        if (n != 1 && n != tree.root && !node.isLeaf()) order.push_back({inefficiency(tree, n), n});
    }
    std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
        return a.first > b.first || (a.first == b.first && a.second < b.second);
    });
    // Earlier reinsertions may have made a node the root; the rest stay inner nodes.
    for (const auto& [measure, n] : order)
        if (n != tree.root) tree.reinsertChildrenOf(n);
}

// The pair layout again, depth-first with the left subtree first, and the leaf arrays in the
// new leaf order.
void emit(const LinkedTree& tree, BinaryBvh& bvh) {
    BinaryBvh out;
    out.nodes.reserve(bvh.nodes.size());
    out.nodes.resize(2);
    out.nodes[1] = BvhNode{{0, 0, 0, 0, 0, 0}, 0, 0};
    out.primIndices.reserve(bvh.primIndices.size());
    out.leafTriangles.reserve(bvh.leafTriangles.size());
    std::vector<std::pair<uint32_t, uint32_t>> stack{{tree.root, 0}};  // linked node, slot
    while (!stack.empty()) {
        const auto [n, slot] = stack.back();
        stack.pop_back();
        const LinkedTree::Node& node = tree.nodes[n];
        out.nodes[slot].setBox(node.box);
        if (node.isLeaf()) {
            out.nodes[slot].index = uint32_t(out.primIndices.size());
            out.nodes[slot].count = node.count;
            out.primIndices.insert(out.primIndices.end(), bvh.primIndices.begin() + node.first,
                                   bvh.primIndices.begin() + node.first + node.count);
            out.leafTriangles.insert(out.leafTriangles.end(), bvh.leafTriangles.begin() + node.first,
                                     bvh.leafTriangles.begin() + node.first + node.count);
            continue;
        }
        const uint32_t pair = uint32_t(out.nodes.size());
        out.nodes[slot].index = pair;
        out.nodes[slot].count = 0;
        out.nodes.resize(pair + 2);
        stack.push_back({node.child[1], pair + 1});
        stack.push_back({node.child[0], pair});
    }
    bvh = std::move(out);
}

}  // namespace

void optimizeByInsertion(BinaryBvh& bvh, int passes) {
    // Fewer than three leaves: no inner node other than the root to take out.
    if (bvh.nodes.size() < 6) return;
    LinkedTree tree(bvh.nodes);
    double area = tree.innerArea();
    bool improved = false;
    for (int pass = 0; pass < passes; ++pass) {
        LinkedTree before = tree;
        optimizePass(tree);
        const double after = tree.innerArea();
        // Greedy reinsertions can lose what they gain elsewhere: keep the better tree.
        if (!(after < area) || tree.nodes[tree.root].height >= kBvhMaxDepth) {
            tree = std::move(before);
            break;
        }
        const bool small = after > 0.99 * area;
        area = after;
        improved = true;
        if (small) break;
    }
    if (improved) emit(tree, bvh);
}

}  // namespace bvhlab
