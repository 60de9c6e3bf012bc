#include "accel/octree/octree_nodes.h"

#include "accel/octree/octree_objects.h"

#include <algorithm>
#include <cmath>

namespace bvhlab::octree {

std::optional<Subdivision> parseSubdivision(std::string_view name) {
    if (name == "centre") return Subdivision::Centre;
    if (name == "adaptive") return Subdivision::Adaptive;
    return std::nullopt;
}

uint64_t Octree::emptyLeaves() const {
    uint64_t empty = 0;
    for (const OctreeNode& n : nodes) empty += n.isLeaf() && n.objects == 0;
    return empty;
}

size_t Octree::maxLeafReferences() const {
    size_t most = 0;
    for (const OctreeNode& n : nodes)
        if (n.isLeaf()) most = std::max<size_t>(most, n.references());
    return most;
}

double adaptiveSplit(View<const Bounds3> boxes, View<const uint32_t> objects, const DVec3& lo, const DVec3& hi,
                     int axis) {
    const double middle = 0.5 * (lo[axis] + hi[axis]);
    if (objects.empty()) return middle;
    std::vector<double> centres;
    centres.reserve(objects.size());
    for (uint32_t p : objects) centres.push_back(0.5 * (double(boxes[p].lower[axis]) + double(boxes[p].upper[axis])));
    const size_t half = centres.size() / 2;
    std::nth_element(centres.begin(), centres.begin() + half, centres.end());
    double median = centres[half];
    if (centres.size() % 2 == 0) median = 0.5 * (median + *std::max_element(centres.begin(), centres.begin() + half));

    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    const double a = hi[axis] - lo[axis], sb = hi[b] - lo[b], sc = hi[c] - lo[c];
    double best = middle, bestCost = kInfinity;
    for (int i = 0; i < kAdaptivePositions; ++i) {
        const double position = middle + (median - middle) * double(i) / double(kAdaptivePositions - 1);
        if (!(position > lo[axis] && position < hi[axis])) continue;
        uint64_t left = 0, right = 0, cut = 0;
        for (uint32_t p : objects) {
            if (double(boxes[p].upper[axis]) < position)
                ++left;
            else if (double(boxes[p].lower[axis]) > position)
                ++right;
            else
                ++cut;
        }
        const double t = position - lo[axis];
        const double cost = double(left + cut) * (t * 2.0 * (sb + sc) + sb * sc) +
                            double(right + cut) * ((a - t) * 2.0 * (sb + sc) + sb * sc);
        if (cost < bestCost) bestCost = cost, best = position;
    }
    return best;
}

namespace {

class Builder {
public:
    Builder(const PrimitiveSet& prims, const OctreeParameters& parameters, Octree& tree)
        : prims_(prims), parameters_(parameters), tree_(tree), objects_(octreeObjects(prims, parameters.polygons)) {
        budget_ = std::max(kMinReferenceBudget, kReferencesPerPrimitive * uint64_t(prims.valid.size()));
    }

    void build() {
        Bounds3 box;
        for (const Bounds3& b : objects_.boxes) box.extend(b);
        const DVec3 lower(box.lower), upper(box.upper);
        const DVec3 extent = upper - lower;
        const double magnitude = std::max({std::abs(lower.x), std::abs(lower.y), std::abs(lower.z), std::abs(upper.x),
                                           std::abs(upper.y), std::abs(upper.z)});
        const double pad = kRootPad * std::max({extent.x, extent.y, extent.z, magnitude}) + 1e-30;
        tree_.lower = lower - pad;
        tree_.upper = upper + pad;
        tree_.objects = objects_.size();
        tree_.nodes.emplace_back();
        std::vector<uint32_t> all(objects_.size());
        for (uint32_t o = 0; o < all.size(); ++o) all[o] = o;
        used_ = all.size();
        node(0, std::move(all), tree_.lower, tree_.upper, 0);
    }

private:
    // Makes node n (already allocated) over `objects` in [lo, hi] at `depth`.
    void node(uint32_t n, std::vector<uint32_t> objects, const DVec3& lo, const DVec3& hi, int depth) {
        if (int(objects.size()) > parameters_.maxObjects && depth < parameters_.maxDepth) {
            DVec3 split;
            for (int a = 0; a < 3; ++a)
                split[a] = parameters_.subdivision == Subdivision::Adaptive
                               ? adaptiveSplit(objects_.boxes, objects, lo, hi, a)
                               : 0.5 * (lo[a] + hi[a]);
            std::vector<uint32_t> children[8];
            uint64_t made = 0;
            for (int c = 0; c < 8; ++c) {
                for (uint32_t o : objects) {
                    const Bounds3& b = objects_.boxes[o];
                    bool touches = true;
                    for (int a = 0; a < 3 && touches; ++a)
                        touches = (c >> a & 1) ? double(b.upper[a]) >= split[a] : double(b.lower[a]) <= split[a];
                    if (touches) children[c].push_back(o);
                }
                made += children[c].size();
            }
            if (used_ + made <= budget_) {
                used_ += made;
                objects = {};
                const uint32_t first = uint32_t(tree_.nodes.size());
                tree_.nodes.resize(tree_.nodes.size() + 8);
                tree_.nodes[n].split = split;
                tree_.nodes[n].firstChild = first;
                for (int c = 0; c < 8; ++c) {
                    DVec3 childLo = lo, childHi = hi;
                    for (int a = 0; a < 3; ++a) ((c >> a & 1) ? childLo : childHi)[a] = split[a];
                    node(first + c, std::move(children[c]), childLo, childHi, depth + 1);
                }
                return;
            }
            tree_.budgetReached = true;
        }
        OctreeNode& leaf = tree_.nodes[n];
        leaf.begin = uint32_t(tree_.refs.size());
        for (uint32_t o : objects)
            for (uint32_t i = objects_.first[o]; i < objects_.first[o + 1]; ++i) tree_.refs.push_back(prims_.valid[i]);
        leaf.end = uint32_t(tree_.refs.size());
        leaf.objects = uint32_t(objects.size());
        tree_.objectReferences += objects.size();
        tree_.deepestLeaf = std::max(tree_.deepestLeaf, depth);
    }

    const PrimitiveSet& prims_;
    const OctreeParameters& parameters_;
    Octree& tree_;
    OctreeObjects objects_;
    uint64_t budget_ = 0, used_ = 0;
};

}  // namespace

Octree buildOctree(const PrimitiveSet& prims, const OctreeParameters& parameters) {
    Octree tree;
    if (prims.valid.empty()) return tree;
    Builder(prims, parameters, tree).build();
    return tree;
}

}  // namespace bvhlab::octree
