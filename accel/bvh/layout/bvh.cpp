#include "accel/bvh/layout/bvh.h"

#include <algorithm>

namespace bvhlab {

void fillTreeStats(const Bvh& bvh, double cTraversal, double cIntersect, BuildStats& stats) {
    size_t nodes = 0, leaves = 0, leafPrims = 0, maxLeafPrims = 0;
    int maxDepth = 0;
    double innerArea = 0.0, leafAreaTimesPrims = 0.0;

    struct Item {
        uint32_t node;
        int depth;
    };
    std::vector<Item> stack;
    if (!bvh.empty()) stack.push_back({0, 0});
    while (!stack.empty()) {
        const auto [index, depth] = stack.back();
        stack.pop_back();
        const BvhNode& node = bvh.nodes[index];
        const double area = node.box().halfArea();
        ++nodes;
        maxDepth = std::max(maxDepth, depth);
        if (node.isLeaf()) {
            ++leaves;
            leafPrims += node.count;
            maxLeafPrims = std::max<size_t>(maxLeafPrims, node.count);
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
    stats.maxDepth = maxDepth;
    stats.depthBound = kBvhMaxDepth;
    stats.bytes = bvh.bytes();

    // A root of zero area (a single axis-aligned segment cannot occur: triangles are
    // non-degenerate, but guard anyway) would divide by zero: count areas as equal then.
    const double rootArea = bvh.empty() ? 0.0 : double(bvh.nodes[0].box().halfArea());
    SahCost sah{0.0, cTraversal, cIntersect};
    if (rootArea > 0.0) {
        sah.cost = (cTraversal * innerArea + cIntersect * leafAreaTimesPrims) / rootArea;
    } else if (!bvh.empty()) {
        sah.cost = cTraversal * double(nodes - leaves) + cIntersect * double(leafPrims);
    }
    stats.sah = sah;
}

}  // namespace bvhlab
