#include "accel/bvh/bvh_env.h"

#include "accel/bvh/traverse/traversal_kernels.h"

#include <span>

namespace bvhlab {

const BvhKeys& bvhCommonKeys() {
    using namespace keys::BVH;
    static const BvhKeys bound = {
        {maxLeaf, [](BvhSettings& s, int v) { s.build.shared.maxLeaf = v; }},
        {leafCap, [](BvhSettings& s, int v) { s.build.shared.leafCap = v; }},
        {cTraversal, [](BvhSettings& s, float v) { s.build.shared.cTraversal = v; }},
        {cIntersect, [](BvhSettings& s, float v) { s.build.shared.cIntersect = v; }},
        {keys::BVH::simd, [](BvhSettings& s, bool v) { s.build.shared.simd = v; }},
        {robust, [](BvhSettings& s, bool v) { s.traversal.robust = v; }},
        {threads, [](BvhSettings& s, int v) { s.build.shared.threads = v; }},
        {epoMaxTriangles, [](BvhSettings& s, int v) { s.stats.epoMaxTriangles = uint32_t(v); }},
        {optimize,
         [](BvhSettings& s, const std::string& v) {
             s.build.optimize = v == "insertion" ? BvhOptimize::Insertion : BvhOptimize::None;
         }},
        {optimizeIterations, [](BvhSettings& s, int v) { s.build.insertion.iterations = v; }},
        {packetFallback, [](BvhSettings& s, int v) { s.traversal.packetFallback = v; }},
        {isa,
         [](BvhSettings& s, const std::string& v) {
             for (Isa i : {Isa::Auto, Isa::Scalar, Isa::Avx2, Isa::Avx512})
                 if (v == isaName(i)) s.traversal.isa = i;
         }},
        {batchTraversal,
         [](BvhSettings& s, const std::string& v) {
             for (BatchTraversal p : {BatchTraversal::Auto, BatchTraversal::Packets, BatchTraversal::Coherent,
                                     BatchTraversal::Stream, BatchTraversal::Single})
                 if (v == batchTraversalName(p)) s.traversal.batchTraversal = p;
         }},
        {singleStep,
         [](BvhSettings& s, const std::string& v) {
             for (SingleStep step : {SingleStep::Offsets, SingleStep::Octant})
                 if (v == singleStepName(step)) s.traversal.singleStep = step;
         }},
    };
    return bound;
}

const BvhKeys& sahTerminationKeys() {
    static const BvhKeys bound = {
        {keys::BVH::sahTermination, [](BvhSettings& s, bool v) { s.build.shared.sahTermination = v; }},
    };
    return bound;
}

const BvhKeys& spatialMedianKeys() {
    static const BvhKeys bound = {
        {keys::BVH::tdbvhSplit,
         [](BvhSettings& s, const std::string& v) {
             s.build.spatialMedian.splitBox = v == "nodebox" ? MedianSplitBox::NodeBox : MedianSplitBox::CentroidBox;
         }},
    };
    return bound;
}

const BvhKeys& binnedSahKeys() {
    static const BvhKeys bound = {
        {keys::BVH::bins, [](BvhSettings& s, int v) { s.build.binnedSah.bins = v; }},
        {keys::BVH::allAxes, [](BvhSettings& s, bool v) { s.build.binnedSah.allAxes = v; }},
    };
    return bound;
}

const BvhKeys& sbvhKeys() {
    static const BvhKeys bound = {
        {keys::BVH::sbvhAlpha, [](BvhSettings& s, float v) { s.build.sbvh.alpha = v; }},
        {keys::BVH::sbvhGrowth, [](BvhSettings& s, float v) { s.build.sbvh.growth = v; }},
    };
    return bound;
}

const BvhKeys& plocKeys() {
    static const BvhKeys bound = {
        {keys::BVH::plocRadius, [](BvhSettings& s, int v) { s.build.ploc.radius = v; }},
    };
    return bound;
}

namespace {

std::span<const BvhKeys* const> allKeys() {
    static const BvhKeys* const all[] = {&bvhCommonKeys(), &sahTerminationKeys(), &spatialMedianKeys(),
                                         &binnedSahKeys(), &sbvhKeys(),           &plocKeys()};
    return all;
}

}  // namespace

void registerBvhKeys(EnvRegistry& registry) {
    for (const BvhKeys* keys : allKeys()) keys->registerWith(registry);
}

BvhSettings bvhSettingsFromEnv(const Env& env) {
    BvhSettings settings;
    for (const BvhKeys* keys : allKeys()) keys->read(env, settings);
    if (settings.build.shared.threads == 0) settings.build.shared.threads = env.get(keys::SetRayTracing::threads);
    return settings;
}

}  // namespace bvhlab
