#include "accel/bvh/builders/merge_tree_builder.h"

#include "accel/bvh/builders/build_steps.h"
#include "accel/bvh/builders/cluster_tree.h"

#include <fmt/core.h>

#include <memory>
#include <stdexcept>

namespace bvhlab {

namespace {

void checkMerges(const std::string& builder, std::span<const uint32_t> children, uint32_t n) {
    auto fail = [&](const std::string& why) {
        return std::runtime_error(fmt::format("builder '{}': its merge tree over {} primitives {}", builder, n, why));
    };
    if (children.size() != 2 * (size_t(n) - 1))
        throw fail(fmt::format("has {} merges, not {}", children.size() / 2.0, n - 1));
    std::vector<uint8_t> used(2 * size_t(n) - 1, 0);
    for (size_t k = 0; k < children.size(); ++k) {
        const uint32_t node = n + uint32_t(k / 2), child = children[k];
        if (child >= node) throw fail(fmt::format("joins node {} into node {}, which is not above it", child, node));
        if (used[child]++) throw fail(fmt::format("uses node {} twice", child));
    }
}

}  // namespace

BinaryBvh buildFromMerges(const std::string& builder, const BuildConfig& config, const PrimitiveSet& prims,
                          const MergeFunction& merge) {
    const uint32_t n = uint32_t(prims.validTriangles().size());
    BinaryBvh bvh;
    if (n == 0) return bvh;
    // Uninitialised storage: every PrimRef is written before it is read.
    const std::unique_ptr<PrimRef[]> refs = std::make_unique_for_overwrite<PrimRef[]>(n);
    const std::unique_ptr<PrimRef[]> ordered = std::make_unique_for_overwrite<PrimRef[]>(n);
    preparePrimRefs(prims, refs.get(), config.simd);
    const std::vector<uint32_t> children = merge({refs.get(), n});
    checkMerges(builder, children, n);

    ClusterTree tree;
    tree.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        const PrimRef& p = refs[i];
        tree.boxes[i] = {{p.lower[0], p.lower[1], p.lower[2], 0.0f}, {p.upper[0], p.upper[1], p.upper[2], 0.0f}};
        formNode(tree, i, config);
    }
    for (uint32_t m = 0; m + 1 < n; ++m) {
        const uint32_t node = n + m, l = children[2 * size_t(m)], r = children[2 * size_t(m) + 1];
        ClusterBox& box = tree.boxes[node];
        for (int a = 0; a < 4; ++a) {
            box.lower[a] = std::min(tree.boxes[l].lower[a], tree.boxes[r].lower[a]);
            box.upper[a] = std::max(tree.boxes[l].upper[a], tree.boxes[r].upper[a]);
        }
        tree.children[2 * size_t(m)] = l;
        tree.children[2 * size_t(m) + 1] = r;
        formNode(tree, node, config);
    }
    bvh.nodes = bvhNodesFromClusterTree(tree, {refs.get(), n}, config, {ordered.get(), n});
    fillLeafArrays(bvh, ordered.get(), prims, config.threads);
    return bvh;
}

}  // namespace bvhlab
