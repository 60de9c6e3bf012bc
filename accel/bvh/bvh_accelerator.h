// The BVH accelerators behind our interface: one class over a node layout, parameterised by the
// builder (builder_table.h, or a plugin's) and the traversal setting. Layout = BinaryBvh is the binary tree
// the builders emit; Layout = WideBvh<N> collapses it by SAH into N-wide nodes (sahbvh4,
// sahbvh8) whose leaves hold their triangles in SIMD blocks of eight. For them the SAH builders
// charge a leaf by the blocks it fills (BuildConfig::sahBlockShift), so their binary tree is
// built for that leaf test; the env keys are the same. Spheres and cones get a binary tree of
// their own by the same builder (layout/quadric_leaves.h), traversed after the triangles'.
#pragma once

#include "accel/bvh/builders/bvh_builder.h"
#include "accel/bvh/layout/wide_bvh.h"
#include "accel/bvh/traverse/traversal_config.h"
#include "accel/bvh/traverse/traversal_kernels.h"
#include "framework/core/accelerator.h"

#include <optional>
#include <string>
#include <string_view>
#include <tuple>

namespace bvhlab {

// What the statistics after a build include (never timed).
struct BvhStatsConfig {
    uint32_t epoMaxTriangles = 1'000'000;  // EPO for scenes of up to this many triangles (0: never)
};

namespace keys::BVH {
inline constexpr FieldKey<&BvhStatsConfig::epoMaxTriangles> epoMaxTriangles{
    "BVH::epoMaxTriangles", 0, 2147483647,
    "statistics: EPO (end-point overlap) after the build, untimed, for scenes of up to this many triangles; 0 = never "
    "(one clipping walk per triangle: about 2 s of CPU per million triangles; the 8.4 M-triangle terrain is above)"};
}  // namespace keys::BVH
inline constexpr std::tuple kBvhStatsKeys{&keys::BVH::epoMaxTriangles};

// What an update does after the primitives moved (Accelerator::update).
enum class BvhUpdate {
    Refit,      // the boxes and the leaves' copies of the primitives recomputed, the tree kept
    Insertion,  // a refit, then the insertion optimiser's passes on the binary tree (collapsed again)
    Rebuild,    // no update: update() returns false and the caller builds again
};
inline constexpr std::string_view kBvhUpdateWords[] = {"refit", "insertion", "rebuild"};

struct BvhUpdateConfig {
    BvhUpdate mode = BvhUpdate::Refit;
};

namespace keys::BVH {
inline constexpr FieldKey<&BvhUpdateConfig::mode> update{
    "BVH::update", kBvhUpdateWords,
    "after primitives moved: refit (boxes recomputed bottom-up, the tree kept), insertion (a refit, then "
    "BVH::optimizeIterations passes of the insertion optimiser; wide layouts collapsed again), or rebuild (no update: "
    "the caller builds again)"};
}  // namespace keys::BVH
inline constexpr std::tuple kBvhUpdateKeys{&keys::BVH::update};

template <typename Layout>
class BvhAccelerator final : public BuildStatsAccelerator {
public:
    BvhAccelerator(BuilderRecord builder, const BvhBuildConfig& build, const TraversalConfig& traversal = {},
                   const BvhStatsConfig& stats = {}, const BvhUpdateConfig& update = {});

    const char* name() const override { return name_.c_str(); }
    // The build includes a collapse to wide nodes and the quadric tree.
    void build(const PrimitiveSet& prims) override;
    // By BVH::update: a refit of the layout (a wide one refitted itself, not collapsed again) and
    // of the quadric tree, parallel on the build's threads; or a refit and the insertion
    // optimiser. Throws std::invalid_argument when the counts of `prims` differ from the build's.
    bool update(const PrimitiveSet& prims) override;
    // #Nodes, #Leaves, depth, SAH and EPO are the binary tree's (the same formula for every
    // builder), with the quadric tree's added (combineTreeStats); memory is the layouts'.
    // Computed on the first call after a build or an update, then kept. After a refit of a wide
    // layout, of its binary tree refitted here (untimed) as the wide one was.
    BuildStats buildStats() const override;
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override;
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override;
    // The kernel's batch call over the triangles (packets on the wide layouts), then, in a
    // scene with quadrics, the quadric tree's part ray by ray as the single-ray calls do it.
    void findNearestBatch(View<const Ray> rays, View<Hit> hits, QueryCounters& counters, View<RayCost> costs,
                          RayCoherence coherence) const override;
    void isOccludedBatch(View<const Ray> rays, View<uint8_t> occluded, QueryCounters& counters, View<RayCost> costs,
                         RayCoherence coherence) const override;

    const Layout& bvh() const { return tree_; }

private:
    // The binary tree the statistics describe: the layout itself, or the one collapsed into it.
    const BinaryBvh& binaryTree() const;
    // The quadric tree's part of a query (after the triangles'), kept out of the hot path.
    [[gnu::noinline]] bool findNearestQuadric(const Ray& ray, bool found, Hit& hit, QueryCounters& counters) const;
    [[gnu::noinline]] bool isOccludedQuadric(const Ray& ray, QueryCounters& counters) const;
    BuilderRecord builder_;
    BvhBuildConfig build_;
    TraversalConfig traversal_;
    // The triangle tree's queries, compiled for the ISA BVH::isa names or the CPU's best
    // (traversal_kernels.h): chosen once, here, with the robustness setting.
    TraversalKernels<Layout> kernels_;
    BvhStatsConfig stats_;
    BvhUpdateConfig update_;
    std::string name_;  // the builder's name, with the width of a wide layout: sahbvh, sahbvh4
    Layout tree_;
    // A wide layout's binary tree, whole from build() to the first buildStats() call: the figures
    // are the binary tree's, and computing them in build() would time them. Its leaf triangles
    // hold most of the memory of the wide tree again, so that call keeps the figures and frees
    // them; the nodes and primitive indices stay, for the statistics after an update and for
    // the insertion update. Empty for Layout = BinaryBvh (tree_ is the binary tree). Not for
    // buildStats() on two threads at once.
    mutable BinaryBvh binary_;
    mutable bool binaryStale_ = false;  // a wide layout was refitted, binary_ not yet
    mutable std::optional<BuildStats> statistics_;
    PrimitiveSet prims_;    // of the last build or update
    size_t triangles_ = 0;  // valid triangles built over
    QuadricBvh quadrics_;   // the spheres and cones, when the scene has any (quadric_leaves.h)
};

// Instantiated for these layouts.
extern template class BvhAccelerator<BinaryBvh>;
extern template class BvhAccelerator<WideBvh<4>>;
extern template class BvhAccelerator<WideBvh<8>>;

}  // namespace bvhlab
