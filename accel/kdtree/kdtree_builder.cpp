#include "accel/kdtree/kdtree_builder.h"

#include "accel/kdtree/kdtree_clip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace bvhlab::kdtree {

namespace {

// At one position the sweep meets the boxes that end there, then the flat ones, then those that
// start there: the order Wald and Havran's counts rely on.
enum EventType : uint32_t { kEnd = 0, kPlanar = 1, kStart = 2 };

struct Event {
    float pos;
    uint32_t word;  // primitive << 2 | type

    uint32_t prim() const { return word >> 2; }
    uint32_t type() const { return word & 3u; }
    bool operator<(const Event& o) const { return pos < o.pos || (pos == o.pos && type() < o.type()); }
};

// A node's events, one list per axis, each sorted.
struct NodeEvents {
    std::vector<Event> axis[3];

    size_t size() const { return axis[0].size() + axis[1].size() + axis[2].size(); }
};

void addEvents(NodeEvents& events, uint32_t prim, const Bounds3& b) {
    for (int a = 0; a < 3; ++a) {
        if (b.lower[a] == b.upper[a]) {
            events.axis[a].push_back({b.lower[a], prim << 2 | kPlanar});
        } else {
            events.axis[a].push_back({b.lower[a], prim << 2 | kStart});
            events.axis[a].push_back({b.upper[a], prim << 2 | kEnd});
        }
    }
}

// Each primitive has one start or one planar event per axis: those of axis 0 list the node's.
template <typename Visit>
void forEachPrimitive(const NodeEvents& events, Visit&& visit) {
    for (const Event& e : events.axis[0])
        if (e.type() != kEnd) visit(e.prim());
}

double halfArea(const DVec3& d) { return d.x * d.y + d.y * d.z + d.z * d.x; }
DVec3 extent(const Bounds3& b) { return DVec3(b.upper) - DVec3(b.lower); }

enum Side : uint8_t { kBoth, kLeftOnly, kRightOnly };

struct Plane {
    int axis = -1;
    float pos = 0.0f;
    bool planarLeft = true;  // where the primitives lying in the plane go
    double cost = kInfinity;
};

class Builder {
public:
    Builder(const PrimitiveSet& prims, const KdTreeParameters& parameters, KdTree& tree)
        : prims_(prims), parameters_(parameters), tree_(tree) {
        const Vec3 magnitude = math::max(math::abs(tree.bounds.lower), math::abs(tree.bounds.upper));
        clipMargin_ = kClipMargin * double(std::max({magnitude.x, magnitude.y, magnitude.z}));
        side_.assign(size_t(prims.coneBase()) + prims.cones.size(), kBoth);
        referenceBudget_ = 16 * prims.valid.size() + (size_t(1) << 20);
        levels_.resize(size_t(tree.maxDepth) + 2);  // sized once: node() holds references into it
    }

    // The root's events: those of every node live in buffers kept per depth (below).
    NodeEvents& rootEvents() { return levelEvents(0, 0); }

    // Builds the node whose events are levelEvents(depth, side), appending it and its subtree.
    void node(int depth, int side, const Bounds3& box) {
        const NodeEvents& events = levelEvents(depth, side);
        size_t n = 0;
        forEachPrimitive(events, [&](uint32_t) { ++n; });
        tree_.eventsSwept += events.size();
        if (n == 0 || depth >= tree_.maxDepth || tree_.references.size() + n > referenceBudget_)
            return leaf(events, depth);
        const Plane plane = findPlane(events, box, n);
        if (plane.axis < 0 || !(plane.cost < parameters_.cIntersect * double(n))) return leaf(events, depth);

        Bounds3 leftBox = box, rightBox = box;
        leftBox.upper[plane.axis] = rightBox.lower[plane.axis] = plane.pos;
        split(events, plane, leftBox, rightBox, levelEvents(depth + 1, 0), levelEvents(depth + 1, 1));
        if (tree_.nodes.size() + 2 > kMaxIndex) throw std::length_error("kdtree: more than 2^30 nodes");
        const size_t self = tree_.nodes.size();
        tree_.nodes.push_back(KdNode::leaf(0, 0));  // made an inner node once its children are placed
        node(depth + 1, 0, leftBox);
        tree_.nodes[self] = KdNode::inner(plane.axis, plane.pos, uint32_t(tree_.nodes.size()));
        node(depth + 1, 1, rightBox);
    }

private:
    double cost(double pl, double pr, size_t nl, size_t nr) const {
        const double lambda = (nl == 0 || nr == 0) ? 1.0 - parameters_.emptyBonus : 1.0;
        return lambda * (parameters_.cTraversal + parameters_.cIntersect * (pl * double(nl) + pr * double(nr)));
    }

    // One sweep per axis over the sorted events (Wald and Havran, algorithm 5): at each position
    // the counts left, right and in the plane follow from the events met so far. Planes on the
    // node's faces cut nothing off and are not candidates.
    Plane findPlane(const NodeEvents& events, const Bounds3& box, size_t n) const {
        Plane best;
        const DVec3 size = extent(box);
        const double area = halfArea(size);
        if (!(area > 0.0)) return best;
        for (int k = 0; k < 3; ++k) {
            const std::vector<Event>& ev = events.axis[k];
            size_t nl = 0, nr = n;
            for (size_t i = 0; i < ev.size();) {
                const float pos = ev[i].pos;
                size_t ends = 0, planars = 0, starts = 0;
                for (; i < ev.size() && ev[i].pos == pos && ev[i].type() == kEnd; ++i) ++ends;
                for (; i < ev.size() && ev[i].pos == pos && ev[i].type() == kPlanar; ++i) ++planars;
                for (; i < ev.size() && ev[i].pos == pos && ev[i].type() == kStart; ++i) ++starts;
                nr -= planars + ends;
                if (pos > box.lower[k] && pos < box.upper[k]) {
                    DVec3 leftSize = size, rightSize = size;
                    leftSize[k] = double(pos) - double(box.lower[k]);
                    rightSize[k] = double(box.upper[k]) - double(pos);
                    const double pl = halfArea(leftSize) / area, pr = halfArea(rightSize) / area;
                    const double planarLeft = cost(pl, pr, nl + planars, nr);
                    const double planarRight = cost(pl, pr, nl, nr + planars);
                    const double c = std::min(planarLeft, planarRight);
                    if (c < best.cost) best = {k, pos, planarLeft <= planarRight, c};
                }
                nl += starts + planars;
            }
        }
        return best;
    }

    // Classifies the primitives against the plane (Wald and Havran, algorithm 6), keeps the
    // events of those on one side in their order, and clips those that straddle it to each child:
    // only their new events are sorted, then merged in.
    void split(const NodeEvents& events, const Plane& plane, const Bounds3& leftBox, const Bounds3& rightBox,
               NodeEvents& left, NodeEvents& right) {
        forEachPrimitive(events, [&](uint32_t prim) { side_[prim] = kBoth; });
        for (const Event& e : events.axis[plane.axis]) {
            const uint32_t type = e.type();
            if (type == kEnd && e.pos <= plane.pos)
                side_[e.prim()] = kLeftOnly;
            else if (type == kStart && e.pos >= plane.pos)
                side_[e.prim()] = kRightOnly;
            else if (type == kPlanar)
                side_[e.prim()] =
                    (e.pos < plane.pos || (e.pos == plane.pos && plane.planarLeft)) ? kLeftOnly : kRightOnly;
        }
        NodeEvents& clippedLeft = clippedLeft_;
        NodeEvents& clippedRight = clippedRight_;
        for (int a = 0; a < 3; ++a) clippedLeft.axis[a].clear(), clippedRight.axis[a].clear();
        forEachPrimitive(events, [&](uint32_t prim) {
            if (side_[prim] != kBoth) return;
            const Bounds3 l = clippedBounds(prims_, prim, leftBox, clipMargin_);
            const Bounds3 r = clippedBounds(prims_, prim, rightBox, clipMargin_);
            if (!l.isEmpty()) addEvents(clippedLeft, prim, l);
            if (!r.isEmpty()) addEvents(clippedRight, prim, r);
        });
        for (int a = 0; a < 3; ++a) {
            size_t leftCount = 0, rightCount = 0;
            for (const Event& e : events.axis[a]) {
                const uint8_t s = side_[e.prim()];
                leftCount += s == kLeftOnly;
                rightCount += s == kRightOnly;
            }
            std::vector<Event>& onlyLeft = left.axis[a];
            std::vector<Event>& onlyRight = right.axis[a];
            onlyLeft.clear(), onlyRight.clear();
            onlyLeft.reserve(leftCount + clippedLeft.axis[a].size());
            onlyRight.reserve(rightCount + clippedRight.axis[a].size());
            for (const Event& e : events.axis[a]) {
                const uint8_t s = side_[e.prim()];
                if (s == kLeftOnly)
                    onlyLeft.push_back(e);
                else if (s == kRightOnly)
                    onlyRight.push_back(e);
            }
            mergeSorted(onlyLeft, clippedLeft.axis[a]);
            mergeSorted(onlyRight, clippedRight.axis[a]);
        }
    }

    // Sorts `added` and merges it into `kept`, in place from the back (`kept` has the room).
    static void mergeSorted(std::vector<Event>& kept, std::vector<Event>& added) {
        std::sort(added.begin(), added.end());
        size_t i = kept.size(), j = added.size(), o = i + j;
        kept.resize(o);
        while (j > 0) kept[--o] = (i > 0 && added[j - 1] < kept[i - 1]) ? kept[--i] : added[--j];
    }

    // One pair of event lists per depth, the children's of the node being split there: the right
    // child's list at depth d + 1 is untouched while the left child's subtree uses depths below,
    // so the lists are reused from node to node without allocating.
    NodeEvents& levelEvents(int depth, int side) { return levels_[size_t(depth)][size_t(side)]; }

    void leaf(const NodeEvents& events, int depth) {
        const size_t first = tree_.references.size();
        forEachPrimitive(events, [&](uint32_t prim) { tree_.references.push_back(prim); });
        const size_t count = tree_.references.size() - first;
        if (first > kMaxIndex || count > kMaxIndex) throw std::length_error("kdtree: more than 2^30 references");
        // Ascending, so that a leaf's order does not depend on where its planes happened to fall.
        std::sort(tree_.references.begin() + ptrdiff_t(first), tree_.references.end());
        tree_.nodes.push_back(KdNode::leaf(uint32_t(first), uint32_t(count)));
        ++tree_.leaves;
        if (count == 0) ++tree_.emptyLeaves;
        tree_.maxLeafReferences = std::max(tree_.maxLeafReferences, count);
        tree_.deepestLeaf = std::max(tree_.deepestLeaf, depth);
    }

    const PrimitiveSet& prims_;
    const KdTreeParameters& parameters_;
    KdTree& tree_;
    double clipMargin_ = 0.0;
    std::vector<std::array<NodeEvents, 2>> levels_;
    NodeEvents clippedLeft_, clippedRight_;  // a split's straddling primitives, clipped to each child
    std::vector<uint8_t> side_;              // per primitive, during one node's split
    size_t referenceBudget_ = 0;             // past it, nodes become leaves: bounded memory on any input
};

Bounds3 primitiveBounds(const PrimitiveSet& prims, uint32_t prim) {
    return prims.kind(prim) == PrimitiveKind::Triangle ? prims.triangles[prim].bounds() : boundsOf(prims.quadric(prim));
}

}  // namespace

int autoMaxDepth(size_t primitives) {
    const double depth = 8.0 + 1.3 * std::log2(double(std::max<size_t>(primitives, 1)));
    return std::clamp(int(std::lround(depth)), 1, 64);
}

KdTree buildKdTree(const PrimitiveSet& prims, const KdTreeParameters& parameters) {
    KdTree tree;
    if (prims.valid.empty()) return tree;
    if (prims.valid.back() > kMaxIndex) throw std::length_error("kdtree: primitive indices beyond 2^30");
    for (uint32_t prim : prims.valid) tree.bounds.extend(primitiveBounds(prims, prim));
    tree.maxDepth = parameters.maxDepth > 0 ? parameters.maxDepth : autoMaxDepth(prims.valid.size());
    // A box that is not finite has no planes to sweep: everything in one leaf.
    const bool finite = isFinite(tree.bounds.lower) && isFinite(tree.bounds.upper);
    if (!finite) tree.maxDepth = 0;
    Builder builder(prims, parameters, tree);
    NodeEvents& events = builder.rootEvents();
    for (int a = 0; a < 3; ++a) events.axis[a].reserve(2 * prims.valid.size());
    for (uint32_t prim : prims.valid) addEvents(events, prim, primitiveBounds(prims, prim));
    if (finite)
        for (auto& axis : events.axis) std::sort(axis.begin(), axis.end());
    builder.node(0, 0, tree.bounds);
    return tree;
}

namespace {

double sahOf(const KdTree& tree, uint32_t index, const Bounds3& box, double cTraversal, double cIntersect) {
    const KdNode& n = tree.nodes[index];
    const double area = halfArea(extent(box));
    if (n.isLeaf()) return cIntersect * area * double(n.references());
    Bounds3 below = box, above = box;
    below.upper[n.axis()] = above.lower[n.axis()] = n.split();
    return cTraversal * area + sahOf(tree, index + 1, below, cTraversal, cIntersect) +
           sahOf(tree, n.aboveChild(), above, cTraversal, cIntersect);
}

}  // namespace

double sahCost(const KdTree& tree, double cTraversal, double cIntersect) {
    const double rootArea = halfArea(extent(tree.bounds));
    if (tree.nodes.empty() || !(rootArea > 0.0) || !std::isfinite(rootArea)) return 0.0;
    return sahOf(tree, 0, tree.bounds, cTraversal, cIntersect) / rootArea;
}

}  // namespace bvhlab::kdtree
