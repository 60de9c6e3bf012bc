// sbvh: the split BVH of Stich, Friedrich and Dietrich, "Spatial Splits in Bounding Volume
// Hierarchies" (HPG 2009). Per node, the binned object split of sahbvh (object_binning.h);
// when its two children overlap by more than alpha * A(root) (SbvhConfig::alpha), also
// spatial splits (spatial_binning.h), which cut the references a plane crosses into chopped
// boxes of the triangle's parts (reference_split.h); the cheaper split wins. A cut reference
// whose whole box on one side costs less than the cut is unsplit. New references
// come from a budget of growth * N (0.3: at most 30 % more references than triangles).
//
// Why not BvhSplitRule and its trySplit hook: spatial splits make ranges grow, and
// BvhSplitRule partitions one array of exactly N PrimRefs in place. Here each node's
// references are a vector of their own (the left child keeps its parent's storage, the right
// one takes a vector from a pool), the leaves write their primitives to an output array, and
// the nodes come from the same recursion (top_down_recursion.h), so the result is the same
// binary BinaryBvh: a cut triangle appears in several leaves, each time
// whole in leafTriangles, so every traversal and the wide collapse read it unchanged.
#pragma once

#include "accel/bvh/builders/build_jobs.h"
#include "accel/bvh/builders/object_binning.h"
#include "accel/bvh/builders/spatial_binning.h"

#include <span>
#include <tuple>
#include <vector>

namespace bvhlab {

// sbvh's own options; its object splits and its spatial bins follow BinnedSahConfig.
struct SbvhConfig {
    float alpha = 1e-5f;  // spatial splits only where the object split's children overlap by more
                          // than alpha * A(root): lower finds more overlap to remove, builds slower
    float growth = 0.3f;  // at most this many new references per triangle: memory for quality

    bool operator==(const SbvhConfig&) const = default;
};

namespace keys::BVH {
inline constexpr FieldKey<&SbvhConfig::alpha> sbvhAlpha{
    "BVH::sbvhAlpha", 0, 1,
    "sbvh: try spatial splits only where the object split's children overlap by more than this fraction of the "
    "root's area (Stich et al. 2009: 1e-5; 0 = everywhere, 1 = never)"};
inline constexpr FieldKey<&SbvhConfig::growth> sbvhGrowth{
    "BVH::sbvhGrowth", 0, 10,
    "sbvh: spatial splits may add at most this many references per triangle (0.3 = 30 % more); none once spent"};
}  // namespace keys::BVH
inline constexpr std::tuple kSbvhKeys{&keys::BVH::sbvhAlpha, &keys::BVH::sbvhGrowth};

// A node under construction: its references, their boxes, and how many new references its
// subtree may still make. The budget is split between children in proportion to their
// references, so that a subtree's tree does not depend on the order subtrees are built in.
struct SbvhRange {
    std::vector<PrimRef> refs;
    Bounds3 bounds, centroidBounds;
    uint32_t budget = 0;
    uint32_t size() const { return uint32_t(refs.size()); }
};

// A node's references shared out between its children (a cut reference in both).
struct SbvhSplit {
    SbvhRange left, right;
};

class SbvhBuilder {
public:
    // rootArea: the half area of the whole tree's root box (alpha is relative to it).
    SbvhBuilder(const BuildConfig& config, const BinnedSahConfig& binned, const SbvhConfig& sbvh,
                std::span<const Triangle> triangles, float rootArea);

    struct Deferred {
        SbvhRange range;
        uint32_t node;
        int depth;
    };
    // The subtree over `root` at `depth` (root at 0, a padding slot, then sibling pairs); its
    // leaves index leafPrims() from 0. With `deferred`, ranges of fewer than `deferBelow`
    // references are not built but appended there, their node slots left to the caller.
    BvhNodes build(SbvhRange root, int depth, std::vector<Deferred>* deferred = nullptr, uint32_t deferBelow = 0);
    // The primitive of every leaf entry, in leaf order.
    std::vector<uint32_t>& leafPrims() { return leafPrims_; }

private:
    std::optional<SbvhSplit> chooseSplit(SbvhRange& range, int depth);
    std::optional<SbvhSplit> trySplit(SbvhRange& range, bool mayBeLeaf);
    // Moves the references to the children: side(ref, left, right) returns which to keep
    // (1 left, 2 right, 3 both, with the boxes it writes). The left child keeps the storage.
    template <typename Side>
    SbvhSplit partition(SbvhRange& range, Side side);
    SbvhSplit splitAtIndex(SbvhRange& range, uint32_t mid);
    SbvhSplit objectMedianSplit(SbvhRange& range, int axis);
    std::vector<PrimRef> takeVector();

    BuildConfig config_;
    std::span<const Triangle> triangles_;
    float minOverlap_;  // alpha * A(root)
    ObjectBinning objectBinning_;
    SpatialBinning spatialBinning_;
    std::vector<uint32_t> leafPrims_;
    std::vector<std::vector<PrimRef>> pool_;  // the storage of finished leaves, for reuse
};

// The whole build over the valid triangles, in parallel jobs below kJobPrimitives references
// (the same tree whatever config.threads).
BinaryBvh buildSbvh(const BuildConfig& config, const BinnedSahConfig& binned, const SbvhConfig& sbvh,
                    const PrimitiveSet& prims);

}  // namespace bvhlab
