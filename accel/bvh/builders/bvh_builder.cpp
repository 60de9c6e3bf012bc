#include "accel/bvh/builders/bvh_builder.h"

#include "accel/bvh/builders/build_jobs.h"
#include "accel/bvh/builders/build_steps.h"

#include <fmt/core.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <stdexcept>

namespace bvhlab {

namespace {

// The nodes over `all` (prepared PrimRefs whose boxes and centres `root` bounds), which it
// reorders into leaf order: the nodes above the jobs, then the jobs' subtrees appended in the
// order they were deferred, so the same tree whatever the thread count and the schedule.
std::vector<BvhNode, TraversalAllocator<BvhNode>> buildNodes(const SplitRuleFactory& makeBuilder,
                                                             const BvhBuildConfig& config, std::span<PrimRef> all,
                                                             const BuildRange& root) {
    std::vector<DeferredRange> jobs;
    std::vector<BvhNode, TraversalAllocator<BvhNode>> nodes =
        makeBuilder(config)->build(all, root, 0, &jobs, kJobPrimitives);
    std::vector<std::vector<BvhNode, TraversalAllocator<BvhNode>>> subtrees(jobs.size());
    onThreads(config.shared.threads, [&] {
        tbb::enumerable_thread_specific<std::unique_ptr<BvhSplitRule>> builders([&] { return makeBuilder(config); });
        tbb::parallel_for(size_t(0), jobs.size(),
                          [&](size_t j) { subtrees[j] = builders.local()->build(all, jobs[j].range, jobs[j].depth); });
    });
    for (size_t j = 0; j < jobs.size(); ++j) appendSubtree(nodes, jobs[j].node, subtrees[j]);
    return nodes;
}

}  // namespace

namespace {

// A plugin's split rule may reorder the PrimRefs, nothing else: each valid triangle once, with
// the box it was given.
void checkPrimRefsOf(const BuilderRecord& builder, const PrimRef* refs, const PrimitiveSet& prims) {
    const std::span<const uint32_t> valid = prims.validTriangles();
    std::vector<uint8_t> seen(prims.triangles.size(), 0);
    for (const uint32_t prim : valid) seen[prim] = 1;
    for (size_t i = 0; i < valid.size(); ++i) {
        const PrimRef& ref = refs[i];
        const bool known = ref.prim < seen.size() && seen[ref.prim] == 1;
        if (known) seen[ref.prim] = 2;
        Bounds3 box;
        if (known)
            for (const Vec3& v :
                 {prims.triangles[ref.prim].v0, prims.triangles[ref.prim].v1, prims.triangles[ref.prim].v2})
                box.extend(v);
        if (!known || ref.box().lower != box.lower || ref.box().upper != box.upper)
            throw std::runtime_error(
                fmt::format("builder '{}' changed the primitives it was to reorder (at index {}: "
                            "primitive {}{})",
                            builder.name, i, ref.prim, known ? ", another box" : ", not one of them once"));
    }
}

// The builder's tree, before any optimisation.
BinaryBvh buildBinary(const BuilderRecord& builder, const BvhBuildConfig& config, const PrimitiveSet& prims) {
    if (builder.wholeTree) return builder.wholeTree(config, prims);
    const size_t n = prims.validTriangles().size();
    // Uninitialised storage: every PrimRef is written by preparePrimRefs.
    const std::unique_ptr<PrimRef[]> refs = std::make_unique_for_overwrite<PrimRef[]>(n);
    const BuildRange root = preparePrimRefs(prims, refs.get(), config.shared.simd);
    BinaryBvh bvh;
    bvh.nodes = buildNodes(builder.splitRule, config, std::span<PrimRef>(refs.get(), n), root);
    if (builder.fromPlugin) checkPrimRefsOf(builder, refs.get(), prims);
    fillLeafArrays(bvh, refs.get(), prims, config.shared.threads);
    return bvh;
}

}  // namespace

BinaryBvh buildBvh(const BuilderRecord& builder, const BvhBuildConfig& config, const PrimitiveSet& prims) {
    BinaryBvh bvh = buildBinary(builder, config, prims);
    if (config.optimize == BvhOptimize::Insertion) optimizeByInsertion(bvh, config.insertion.iterations);
    return bvh;
}

std::vector<BvhNode, TraversalAllocator<BvhNode>> buildOverBoxes(const BvhBuildConfig& config, std::span<PrimRef> refs,
                                                                 const SplitRuleFactory& rule) {
    const SplitRuleFactory binnedSah = [](const BvhBuildConfig& c) {
        return std::make_unique<BinnedSahBuilder>(c.shared, c.binnedSah);
    };
    BoundsAccumulator<simd::Scalar<4>> acc;
    for (const PrimRef& ref : refs) acc.add(ref);
    return buildNodes(rule ? rule : binnedSah, config, refs,
                      {0, uint32_t(refs.size()), acc.bounds(), acc.centroidBounds()});
}

QuadricBvh buildQuadricBvh(const BuilderRecord& builder, const BvhBuildConfig& config, const PrimitiveSet& prims) {
    // Few primitives as a rule (the SPD scenes have thousands, not millions): plain loops. The
    // builders of whole trees are for the millions of triangles (ploc) or clip them (sbvh); their
    // spheres and cones get binned SAH, as a plugin's do.
    const std::span<const uint32_t> valid = prims.validQuadrics();
    std::vector<PrimRef> refs(valid.size());
    for (size_t i = 0; i < valid.size(); ++i) refs[i] = PrimRef::of(boundsOf(prims.quadric(valid[i])), valid[i]);
    QuadricBvh bvh;
    bvh.nodes = buildOverBoxes(config, refs, builder.fromPlugin ? SplitRuleFactory() : builder.splitRule);
    for (const PrimRef& ref : refs) {
        bvh.primIndices.push_back(ref.prim);
        bvh.leafShapes.push_back(prims.quadric(ref.prim));
    }
    return bvh;
}

}  // namespace bvhlab
