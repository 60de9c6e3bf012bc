#include "accel/bvh/layout/binary_bvh.h"

#include <algorithm>

namespace bvhlab {

void fillTreeStats(std::span<const BvhNode> tree, double cTraversal, double cIntersect, BuildStats& stats) {
    size_t nodes = 0, leaves = 0, leafPrims = 0, maxLeafPrims = 0;
    int maxDepth = 0;
    double innerArea = 0.0, leafAreaTimesPrims = 0.0;

    struct Item {
        uint32_t node;
        int depth;
    };
    std::vector<Item> stack;
    std::vector<size_t> leafSizes;
    if (!tree.empty()) stack.push_back({0, 0});
    while (!stack.empty()) {
        const auto [index, depth] = stack.back();
        stack.pop_back();
        const BvhNode& node = tree[index];
        const double area = node.box().halfArea();
        ++nodes;
        maxDepth = std::max(maxDepth, depth);
        if (node.isLeaf()) {
            ++leaves;
            leafPrims += node.count;
            maxLeafPrims = std::max<size_t>(maxLeafPrims, node.count);
            if (leafSizes.size() <= node.count) leafSizes.resize(node.count + 1, 0);
            ++leafSizes[node.count];
            leafAreaTimesPrims += area * node.count;
        } else {
            innerArea += area;
            stack.push_back({node.index + 1, depth + 1});
            stack.push_back({node.index, depth + 1});
        }
    }

    stats.nodes = nodes;
    stats.leaves = leaves;
    stats.avgLeafPrimitives = leaves ? double(leafPrims) / double(leaves) : 0.0;
    stats.maxLeafPrimitives = maxLeafPrims;
    stats.leafSizes = std::move(leafSizes);
    stats.maxDepth = maxDepth;
    stats.depthBound = kBvhMaxDepth;

    // A root of zero area (a single axis-aligned segment cannot occur: triangles are
    // non-degenerate, but guard anyway) would divide by zero: count areas as equal then.
    const double rootArea = tree.empty() ? 0.0 : double(tree[0].box().halfArea());
    SahCost sah{0.0, cTraversal, cIntersect};
    if (rootArea > 0.0) {
        sah.cost = (cTraversal * innerArea + cIntersect * leafAreaTimesPrims) / rootArea;
    } else if (!tree.empty()) {
        sah.cost = cTraversal * double(nodes - leaves) + cIntersect * double(leafPrims);
    }
    stats.sah = sah;
}

void combineTreeStats(BuildStats& first, const Bounds3& firstRoot, const BuildStats& second,
                      const Bounds3& secondRoot) {
    const auto sum = [](const auto& a, const auto& b) { return a && b ? std::optional(*a + *b) : (a ? a : b); };
    const size_t leaves = first.leaves.value_or(0) + second.leaves.value_or(0);
    if (leaves > 0) {
        first.avgLeafPrimitives = (first.avgLeafPrimitives.value_or(0.0) * double(first.leaves.value_or(0)) +
                                   second.avgLeafPrimitives.value_or(0.0) * double(second.leaves.value_or(0))) /
                                  double(leaves);
    }
    first.nodes = sum(first.nodes, second.nodes);
    first.leaves = sum(first.leaves, second.leaves);
    first.bytes = sum(first.bytes, second.bytes);
    first.primitives += second.primitives;
    first.maxLeafPrimitives = std::max(first.maxLeafPrimitives.value_or(0), second.maxLeafPrimitives.value_or(0));
    first.maxDepth = std::max(first.maxDepth.value_or(0), second.maxDepth.value_or(0));
    if (first.leafSizes.size() < second.leafSizes.size()) first.leafSizes.resize(second.leafSizes.size(), 0);
    for (size_t k = 0; k < second.leafSizes.size(); ++k) first.leafSizes[k] += second.leafSizes[k];
    // EPO is of the triangles' geometry: with spheres and cones beside them it is not known.
    if (!second.epo) first.epo.reset();
    if (first.sah && second.sah) {
        const double unionArea = unionOf(firstRoot, secondRoot).halfArea();
        const double a = unionArea > 0.0 ? firstRoot.halfArea() / unionArea : 1.0;
        const double b = unionArea > 0.0 ? secondRoot.halfArea() / unionArea : 1.0;
        first.sah->cost = a * first.sah->cost + b * second.sah->cost;
    } else if (second.sah) {
        first.sah = second.sah;
    }
}

}  // namespace bvhlab
