// A BVH build as an accelerator asks for it: the builder, named and made by its record, with the
// options of every builder (each reads its own and the shared ones), and what runs after it.
#pragma once

#include "accel/bvh/builders/binned_sah_builder.h"
#include "accel/bvh/builders/insertion_optimizer.h"
#include "accel/bvh/builders/ploc_builder.h"
#include "accel/bvh/builders/sbvh_builder.h"
#include "accel/bvh/builders/spatial_median_builder.h"
#include "accel/bvh/builders/split_rule.h"
#include "accel/bvh/layout/quadric_leaves.h"

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <tuple>

namespace bvhlab {

// What runs after the builder on its binary tree.
enum class BvhOptimize {
    None,
    Insertion,  // insertion_optimizer.h (Bittner et al. 2013)
};
inline constexpr std::string_view kBvhOptimizeWords[] = {"none", "insertion"};

struct BvhBuildConfig {
    BuildConfig shared;
    SpatialMedianConfig spatialMedian;
    BinnedSahConfig binnedSah;  // sahbvh, sbvh's object splits, and the spheres and cones of all
    SbvhConfig sbvh;
    PlocConfig ploc;
    BvhOptimize optimize = BvhOptimize::None;
    InsertionConfig insertion;

    bool operator==(const BvhBuildConfig&) const = default;
};

namespace keys::BVH {
inline constexpr FieldKey<&BvhBuildConfig::optimize> optimize{
    "BVH::optimize", kBvhOptimizeWords,
    "after the builder: none, or insertion (Bittner et al. 2013: inner nodes taken out and their children "
    "reinserted where the SAH grows least; the leaves stay; timed as part of the build)"};
}  // namespace keys::BVH
inline constexpr std::tuple kBvhOptimizeKeys{&keys::BVH::optimize};

// A builder's record: its name and how it makes the binary tree, by a split rule under the shared
// recursion (BvhSplitRule) or by a whole tree of its own (sbvh's growing ranges, ploc's clustering).
// accel/bvh/builder_table.cpp names ours; a plugin's comes from <bvhlab/builder.h>.
using SplitRuleFactory = std::function<std::unique_ptr<BvhSplitRule>(const BvhBuildConfig&)>;
struct BuilderRecord {
    std::string name;  // "sahbvh": the binary accelerator's name
    // Exactly one of the two. splitRule is called once per build thread.
    SplitRuleFactory splitRule;
    // The triangles' tree; spheres and cones then get binned SAH (no triangle to clip, and few).
    std::function<BinaryBvh(const BvhBuildConfig&, const PrimitiveSet&)> wholeTree;
    // A plugin's: after its split rule, the triangles' PrimRefs are checked to be the ones it was
    // given, reordered; spheres and cones get binned SAH (unchecked, a rule could lose one).
    bool fromPlugin = false;
};

// The whole build: PrimRefs from the valid triangles (SIMD or scalar), the builder's recursion
// or its own tree, then the leaf arrays (primitive indices and triangles in leaf order), then
// the optimisation the config asks for.
BinaryBvh buildBvh(const BuilderRecord& builder, const BvhBuildConfig& config, const PrimitiveSet& prims);

// A tree over boxes, `refs` reordered into leaf order (leaf l holds refs[l.index, l.index +
// l.count)), by `rule` (none: binned SAH): the spheres' and cones' tree, a two-level structure's
// top level.
std::vector<BvhNode, TraversalAllocator<BvhNode>> buildOverBoxes(const BvhBuildConfig& config, std::span<PrimRef> refs,
                                                                 const SplitRuleFactory& rule = {});

// buildBvh over the valid spheres and cones (their boxes), with their shapes in leaf order.
QuadricBvh buildQuadricBvh(const BuilderRecord& builder, const BvhBuildConfig& config, const PrimitiveSet& prims);

}  // namespace bvhlab
