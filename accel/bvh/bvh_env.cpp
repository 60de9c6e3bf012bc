#include "accel/bvh/bvh_env.h"

namespace bvhlab {

void registerBvhKeys(EnvRegistry& r) {
    using namespace keys::BVH;
    for (const IntKey& key : {maxLeaf, leafCap, bins, plocRadius, threads, epoMaxTriangles, optimizeIterations,
                               packetFallback}) r.add(key);
    for (const BoolKey& key : {sahTermination, allAxes, keys::BVH::simd, robust}) r.add(key);
    for (const FloatKey& key : {cTraversal, cIntersect, sbvhAlpha, sbvhGrowth}) r.add(key);
    r.add(tdbvhSplit);
    r.add(optimize);
    r.add(isa);
}

std::vector<std::string_view> bvhCommonKeys() {
    using namespace keys::BVH;
    return {maxLeaf.name(), leafCap.name(), cTraversal.name(),      cIntersect.name(), keys::BVH::simd.name(),
            robust.name(),  threads.name(), epoMaxTriangles.name(), optimize.name(),   optimizeIterations.name(),
            packetFallback.name(), isa.name()};
}

BvhBuildConfig bvhConfigFromEnv(const Env& env) {
    using namespace keys::BVH;
    BvhBuildConfig c;
    c.shared.maxLeaf = env.get(maxLeaf);
    c.shared.leafCap = env.get(leafCap);
    c.shared.sahTermination = env.get(sahTermination);
    c.shared.cTraversal = env.get(cTraversal);
    c.shared.cIntersect = env.get(cIntersect);
    c.shared.simd = env.get(keys::BVH::simd);
    c.shared.threads = env.get(threads);
    if (c.shared.threads == 0) c.shared.threads = env.get(keys::SetRayTracing::threads);
    c.binnedSah.bins = env.get(bins);
    c.binnedSah.allAxes = env.get(allAxes);
    c.sbvh.alpha = env.get(sbvhAlpha);
    c.sbvh.growth = env.get(sbvhGrowth);
    c.ploc.radius = env.get(plocRadius);
    c.spatialMedian.splitBox = env.get(tdbvhSplit) == "nodebox" ? MedianSplitBox::NodeBox : MedianSplitBox::CentroidBox;
    c.optimize = env.get(optimize) == "insertion" ? BvhOptimize::Insertion : BvhOptimize::None;
    c.insertion.iterations = env.get(optimizeIterations);
    return c;
}

BvhStatsConfig statsConfigFromEnv(const Env& env) {
    return {uint32_t(env.get(keys::BVH::epoMaxTriangles))};
}

TraversalConfig traversalConfigFromEnv(const Env& env) {
    TraversalConfig c;
    c.robust = env.get(keys::BVH::robust);
    c.packetFallback = env.get(keys::BVH::packetFallback);
    const std::string isa = env.get(keys::BVH::isa);
    for (Isa i : {Isa::Auto, Isa::Scalar, Isa::Avx2, Isa::Avx512})
        if (isa == isaName(i)) c.isa = i;
    return c;
}

}  // namespace bvhlab
