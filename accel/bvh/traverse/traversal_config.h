// How a BVH is traversed, apart from how it is built (BvhBuildConfig): the same tree serves
// either setting.
#pragma once

namespace bvhlab {

// BVH::isa: which compilation of the traversal kernels runs (traversal_kernels.h). Auto: the
// best the CPU runs.
enum class Isa { Auto, Scalar, Avx2, Avx512 };

// BVH::batchTraversal: how the wide layouts trace a batch. Auto follows the batch's coherence
// hint; the others force one path whatever the hint, so that paths can be timed against each
// other as contenders in one run. Every path answers bit for bit alike.
enum class BatchTraversal { Auto, Packets, Coherent, Stream, Single };

// BVH::singleStep: how the wide layouts' single-ray loop finds a node's near and far bounds
// (box_test.h, WideBoxTest): at byte offsets chosen per ray, or as members of a loop compiled
// per direction octant. Both answer bit for bit alike; the key is there to time them.
enum class SingleStep { Offsets, Octant };

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

}  // namespace bvhlab
