// The env keys of the BVH accelerators (builder_table.h), all in section BVH::, each declared
// once here and bound once, in bvh_env.cpp, to the setting it fills: the bindings register the
// keys, list those each accelerator reads and read them.
#pragma once

#include "accel/bvh/builders/bvh_builder.h"
#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/traverse/traversal_config.h"
#include "framework/config/common_keys.h"
#include "framework/config/env.h"
#include "framework/config/key_bindings.h"

namespace bvhlab {

namespace keys::BVH {
inline constexpr IntKey maxLeaf{
    "BVH::maxLeaf", "2", 1, 64,
    "ranges of this many primitives or fewer become leaves; 1, with sahTermination off and leafCap 1, = the "
    "report's BVH"};
inline constexpr IntKey leafCap{
    "BVH::leafCap", "16", 1, 256,
    "largest leaf made when SAH termination stops or all centres coincide (raised to maxLeaf if below)"};
inline constexpr BoolKey sahTermination{"BVH::sahTermination", "true",
                                        "sahbvh/sweepbvh: leaf when C_trav + C_isect*(A_L*N_L + A_R*N_R)/A >= C_isect*N"};
inline constexpr FloatKey cTraversal{"BVH::cTraversal", "1", 0, 1e6,
                                     "SAH cost of an inner node: used by the SAH builders and by the reported SAH cost"};
inline constexpr FloatKey cIntersect{
    "BVH::cIntersect", "1", 1e-6, 1e6,
    "SAH cost of a ray-triangle test: used by the SAH builders and by the reported SAH cost"};
inline constexpr IntKey bins{"BVH::bins", "16", 2, 256, "sahbvh: bins per axis (Wald 2007: 16 suffices)"};
inline constexpr IntKey plocRadius{
    "BVH::plocRadius", "16", 1, 256,
    "ploc: clusters on either side (Morton order) among which each cluster looks for its nearest neighbour"};
inline constexpr BoolKey allAxes{"BVH::allAxes", "false",
                                 "sahbvh: bin all three axes and take the best, not only the widest"};
inline constexpr FloatKey sbvhAlpha{
    "BVH::sbvhAlpha", "1e-5", 0, 1,
    "sbvh: try spatial splits only where the object split's children overlap by more than this fraction of the "
    "root's area (Stich et al. 2009: 1e-5; 0 = everywhere, 1 = never)"};
inline constexpr FloatKey sbvhGrowth{
    "BVH::sbvhGrowth", "0.3", 0, 10,
    "sbvh: spatial splits may add at most this many references per triangle (0.3 = 30 % more); none once spent"};
inline constexpr BoolKey simd{"BVH::simd", "true",
                              "SSE in the build's hot loops (bounds, centres, binning, partition); false = scalar, same tree"};
inline constexpr BoolKey robust{
    "BVH::robust", "true",
    "traversal: watertight triangle test and conservative box test; false = Moeller-Trumbore and plain boxes "
    "(not watertight), only to measure what robustness costs"};
inline constexpr IntKey packetFallback{
    "BVH::packetFallback", "2", 0, 1024,
    "batch queries on the wide layouts (sahbvh4, sahbvh8) trace packets of 8 consecutive rays (16 with AVX-512); a "
    "node reached by at most this many rays of a packet is finished ray by ray (Benthin et al. 2012); 16 or more = "
    "every ray alone. Answers are the same whatever the value"};
inline constexpr std::string_view kIsas[] = {"auto", "scalar", "avx2", "avx512"};
inline constexpr ChoiceKey isa{
    "BVH::isa", "auto", kIsas,
    "traversal: the SIMD kernels to run, auto = the best this CPU runs (avx512, avx2: x86-64-v4, -v3; scalar: the "
    "x86-64 baseline); all answer bit for bit alike; one the CPU cannot run is an error"};
inline constexpr std::string_view kBatchTraversals[] = {"auto", "packets", "coherent", "stream", "single"};
inline constexpr ChoiceKey batchTraversal{
    "BVH::batchTraversal", "auto", kBatchTraversals,
    "batch queries on the wide layouts: auto = by the batch's coherence hint (incoherent: stream; coherent closest "
    "hit: coherent; coherent any hit: packets with AVX-512, else stream); packets (Benthin et al. 2012), coherent "
    "(packets with a frustum test per node and one triangle against all rays at leaves, after Embree's coherent "
    "hybrid traversal), stream (Embree's incoherent streams: 64 rays, each with its single-ray box test at a node), "
    "single (ray by ray): one path whatever the hint, to time paths against each other. Answers are the same "
    "whatever the value"};
inline constexpr std::string_view kSingleSteps[] = {"offsets", "octant"};
inline constexpr ChoiceKey singleStep{
    "BVH::singleStep", "offsets", kSingleSteps,
    "single rays on the wide layouts: offsets = a node's near and far bounds at offsets chosen per ray; octant = the "
    "loop compiled per direction octant, the bounds at fixed offsets (as tinybvh's BVH8_CPU). Answers are the same "
    "whatever the value; there to time the two"};
inline constexpr IntKey threads{"BVH::threads", "0", 0, 1024,
                                "build threads; 0 = as SetRayTracing::threads (0 there: all hardware threads). The "
                                "tree is the same whatever the count"};
inline constexpr IntKey epoMaxTriangles{
    "BVH::epoMaxTriangles", "1000000", 0, 2147483647,
    "statistics: EPO (end-point overlap) after the build, untimed, for scenes of up to this many triangles; 0 = never "
    "(one clipping walk per triangle: about 2 s of CPU per million triangles; the 8.4 M-triangle terrain is above)"};
inline constexpr std::string_view kMedianSplitBoxes[] = {"centroidbox", "nodebox"};
inline constexpr ChoiceKey tdbvhSplit{"BVH::tdbvhSplit", "centroidbox", kMedianSplitBoxes,
                                      "tdbvh: halve the longest axis of the box of the centres, or of the node's box"};
inline constexpr std::string_view kOptimizations[] = {"none", "insertion"};
inline constexpr ChoiceKey optimize{
    "BVH::optimize", "none", kOptimizations,
    "after the builder: none, or insertion (Bittner et al. 2013: inner nodes taken out and their children "
    "reinserted where the SAH grows least; the leaves stay; timed as part of the build)"};
inline constexpr IntKey optimizeIterations{
    "BVH::optimizeIterations", "3", 1, 100,
    "insertion: at most this many passes over all inner nodes, fewer once a pass lowers the inner nodes' area by "
    "under 1 %"};
}  // namespace keys::BVH

// Everything a BVH accelerator is configured with.
struct BvhSettings {
    BvhBuildConfig build;
    TraversalConfig traversal;
    BvhStatsConfig stats;
};

using BvhKeys = KeyBindings<BvhSettings>;

// The keys every BVH accelerator reads, whatever its builder.
const BvhKeys& bvhCommonKeys();
// The keys of the builders' own options; builder_table.cpp says which builder reads which.
const BvhKeys& sahTerminationKeys();
const BvhKeys& spatialMedianKeys();
const BvhKeys& binnedSahKeys();
const BvhKeys& sbvhKeys();
const BvhKeys& plocKeys();

void registerBvhKeys(EnvRegistry& registry);

// Every BVH key's value (a builder uses its own and the shared ones).
BvhSettings bvhSettingsFromEnv(const Env& env);

}  // namespace bvhlab
