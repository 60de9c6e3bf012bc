// How a BVH is traversed, apart from how it is built (BvhBuildConfig): the same tree serves
// either setting.
#pragma once

#include "framework/config/field_key.h"

#include <string_view>
#include <tuple>

namespace bvhlab {

// BVH::isa: which compilation of the traversal kernels runs (traversal_kernels.h). Auto: the
// best the CPU runs.
enum class Isa { Auto, Scalar, Avx2, Avx512 };
inline constexpr std::string_view kIsaWords[] = {"auto", "scalar", "avx2", "avx512"};

// BVH::batchTraversal: how the wide layouts trace a batch. Auto follows the batch's coherence
// hint; the others force one path whatever the hint, so that paths can be timed against each
// other as contenders in one run. Every path answers bit for bit alike.
enum class BatchTraversal { Auto, Packets, Coherent, Stream, Single };
inline constexpr std::string_view kBatchTraversalWords[] = {"auto", "packets", "coherent", "stream", "single"};

// BVH::singleStep: how the wide layouts' single-ray loop finds a node's near and far bounds
// (box_test.h, WideBoxTest): at byte offsets chosen per ray, or as members of a loop compiled
// per direction octant. Both answer bit for bit alike; the key is there to time them.
enum class SingleStep { Offsets, Octant };
inline constexpr std::string_view kSingleStepWords[] = {"offsets", "octant"};

struct TraversalConfig {
    // BVH::robust. true: the watertight triangle test and the conservative box test (box_test.h);
    // false: Moeller-Trumbore and plain boxes (not watertight), only to measure what
    // robustness costs.
    bool robust = true;
    // BVH::packetFallback. Batches on the wide layouts trace packets (packet_traversal.h); a
    // node reached by at most this many active rays of a packet is finished ray by ray.
    // Measured best: docs/performance.md, "Studies".
    int packetFallback = 2;
    // BVH::isa.
    Isa isa = Isa::Auto;
    // BVH::batchTraversal.
    BatchTraversal batchTraversal = BatchTraversal::Auto;
    // BVH::singleStep.
    SingleStep singleStep = SingleStep::Offsets;
};

namespace keys::BVH {
inline constexpr FieldKey<&TraversalConfig::robust> robust{
    "BVH::robust",
    "traversal: watertight triangle test and conservative box test; false = Moeller-Trumbore and plain boxes "
    "(not watertight), only to measure what robustness costs"};
inline constexpr FieldKey<&TraversalConfig::packetFallback> packetFallback{
    "BVH::packetFallback", 0, 1024,
    "batch queries on the wide layouts (sahbvh4, sahbvh8) trace packets of 8 consecutive rays (16 with AVX-512); a "
    "node reached by at most this many rays of a packet is finished ray by ray (Benthin et al. 2012); 16 or more = "
    "every ray alone. Answers are the same whatever the value"};
inline constexpr FieldKey<&TraversalConfig::isa> isa{
    "BVH::isa", kIsaWords,
    "traversal: the SIMD kernels to run, auto = the best this CPU runs (avx512, avx2: x86-64-v4, -v3; scalar: the "
    "x86-64 baseline); all answer bit for bit alike; one the CPU cannot run is an error"};
inline constexpr FieldKey<&TraversalConfig::batchTraversal> batchTraversal{
    "BVH::batchTraversal", kBatchTraversalWords,
    "batch queries on the wide layouts: auto = by the batch's coherence hint (incoherent: stream; coherent closest "
    "hit: coherent; coherent any hit: packets with AVX-512, else stream); packets (Benthin et al. 2012), coherent "
    "(packets with a frustum test per node and one triangle against all rays at leaves, after Embree's coherent "
    "hybrid traversal), stream (Embree's incoherent streams: 64 rays, each with its single-ray box test at a node), "
    "single (ray by ray): one path whatever the hint, to time paths against each other. Answers are the same "
    "whatever the value"};
inline constexpr FieldKey<&TraversalConfig::singleStep> singleStep{
    "BVH::singleStep", kSingleStepWords,
    "single rays on the wide layouts: offsets = a node's near and far bounds at offsets chosen per ray; octant = the "
    "loop compiled per direction octant, the bounds at fixed offsets (as tinybvh's BVH8_CPU). Answers are the same "
    "whatever the value; there to time the two"};
}  // namespace keys::BVH

// The keys of the tests a traversal runs, and those of its kernels and paths.
inline constexpr std::tuple kTraversalTestKeys{&keys::BVH::robust};
inline constexpr std::tuple kTraversalPathKeys{&keys::BVH::packetFallback, &keys::BVH::isa, &keys::BVH::batchTraversal,
                                               &keys::BVH::singleStep};

}  // namespace bvhlab
