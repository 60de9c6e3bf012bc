#include "accel/bvh/bvh_env.h"

namespace bvhlab {

void registerBvhKeys(EnvRegistry& r) {
    using T = EnvType;
    const BvhBuildConfig d;
    r.add({"BVH::maxLeaf", T::Int, std::to_string(d.maxLeaf),
           "ranges of this many primitives or fewer become leaves; 1, with sahTermination off and leafCap 1, = the "
           "report's BVH",
           1, 64, {}});
    r.add({"BVH::leafCap", T::Int, std::to_string(d.leafCap),
           "largest leaf made when SAH termination stops or all centres coincide (raised to maxLeaf if below)", 1, 256,
           {}});
    r.add({"BVH::sahTermination", T::Bool, "true",
           "sahbvh/sweepbvh: leaf when C_trav + C_isect*(A_L*N_L + A_R*N_R)/A >= C_isect*N", 0, 0, {}});
    r.add({"BVH::cTraversal", T::Float, "1",
           "SAH cost of an inner node: used by the SAH builders and by the reported SAH cost", 0, 1e6, {}});
    r.add({"BVH::cIntersect", T::Float, "1",
           "SAH cost of a ray-triangle test: used by the SAH builders and by the reported SAH cost", 1e-6, 1e6, {}});
    r.add({"BVH::bins", T::Int, std::to_string(d.bins), "sahbvh: bins per axis (Wald 2007: 16 suffices)", 2, 256, {}});
    r.add({"BVH::allAxes", T::Bool, "false", "sahbvh: bin all three axes and take the best, not only the widest", 0, 0,
           {}});
    r.add({"BVH::simd", T::Bool, "true",
           "SSE in the build's hot loops (bounds, centres, binning, partition); false = scalar, same tree", 0, 0, {}});
    r.add({"BVH::robust", T::Bool, "true",
           "traversal: watertight triangle test and conservative box test; false = Moeller-Trumbore and plain boxes "
           "(not watertight), only to measure what robustness costs",
           0, 0, {}});
    r.add({"BVH::tdbvhSplit", T::Choice, "centroidbox",
           "tdbvh: halve the longest axis of the box of the centres, or of the node's box", 0, 0,
           {"centroidbox", "nodebox"}});
}

std::vector<std::string> bvhEnvKeys(BvhKind kind) {
    std::vector<std::string> keys = {"BVH::maxLeaf", "BVH::leafCap", "BVH::cTraversal", "BVH::cIntersect", "BVH::simd", "BVH::robust"};
    switch (kind) {
    case BvhKind::SpatialMedian: keys.push_back("BVH::tdbvhSplit"); break;
    case BvhKind::BinnedSah:
        keys.insert(keys.end(), {"BVH::sahTermination", "BVH::bins", "BVH::allAxes"});
        break;
    case BvhKind::SweepSah: keys.push_back("BVH::sahTermination"); break;
    }
    return keys;
}

BvhBuildConfig bvhConfigFromEnv(const Env& env) {
    BvhBuildConfig c;
    c.maxLeaf = env.getInt("BVH::maxLeaf");
    c.leafCap = env.getInt("BVH::leafCap");
    c.sahTermination = env.getBool("BVH::sahTermination");
    c.cTraversal = env.getFloat("BVH::cTraversal");
    c.cIntersect = env.getFloat("BVH::cIntersect");
    c.bins = env.getInt("BVH::bins");
    c.allAxes = env.getBool("BVH::allAxes");
    c.simd = env.getBool("BVH::simd");
    c.robust = env.getBool("BVH::robust");
    c.medianSplitBox = env.getString("BVH::tdbvhSplit") == "nodebox" ? MedianSplitBox::NodeBox : MedianSplitBox::CentroidBox;
    return c;
}

}  // namespace bvhlab
