// One ISA's traversal kernels (traversal_kernels.h): compiled once per ISA with its -march and
// -DBVHLAB_KERNEL_NS=<isa> -DBVHLAB_KERNEL_ISA=Isa::<Isa> (accel/CMakeLists.txt), so that all it
// instantiates lives in namespace bvhlab::<isa> (kernel_namespace.h) and the table it exports is
// kernels::<isa>. The entry points themselves have internal linkage.
#include "accel/bvh/traverse/binary_bvh_traversal.h"
#include "accel/bvh/traverse/packet_traversal.h"
#include "accel/bvh/traverse/stream_traversal.h"
#include "accel/bvh/traverse/traversal_kernels.h"
#include "accel/bvh/traverse/wide_bvh_traversal.h"

#include <type_traits>

#ifndef BVHLAB_KERNEL_ISA
#error "compiled per ISA only: accel/CMakeLists.txt defines BVHLAB_KERNEL_NS and BVHLAB_KERNEL_ISA"
#endif

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {
namespace {

template <typename Tree, bool Robust, bool Counting, SingleStep Step>
bool findNearestKernel(const Tree& tree, const Ray& ray, Hit& hit, QueryCounters& counters) {
    return answerOf(tree, runQuery<ClosestHitQuery, Robust, Counting, Step>(tree, ray, counters), hit);
}

template <typename Tree, bool Robust, bool Counting, SingleStep Step>
bool isOccludedKernel(const Tree& tree, const Ray& ray, QueryCounters& counters) {
    return runQuery<AnyHitQuery, Robust, Counting, Step>(tree, ray, counters).occluded;
}

// The path a batch of Query takes on a wide layout: BVH::batchTraversal, or for Auto the fastest
// for the hint and the query, as timed against each other (docs/performance.md): incoherent
// batches as streams; coherent closest-hit batches (camera rays) as coherent packets, whose
// leaves test one triangle against all rays; coherent any-hit batches (shadow rays, which stop
// early and leave packets thin) as plain packets where they are 16 rays wide (AVX-512), as
// streams where they would be 8.
template <typename Query>
BatchTraversal batchPath(const TraversalConfig& config, RayCoherence coherence) {
    if (config.batchTraversal != BatchTraversal::Auto) return config.batchTraversal;
    if (coherence == RayCoherence::Incoherent) return BatchTraversal::Stream;
    if constexpr (!Query::kStopsAtFirstHit) return BatchTraversal::Coherent;
    return kPacketWidth == 16 ? BatchTraversal::Packets : BatchTraversal::Stream;
}

// Hands each ray's query and work to answer(i, query, work): the wide layouts trace the rays by
// the batch's path (packets, coherent: packet_traversal.h; streams: stream_traversal.h), the binary
// one ray by ray.
template <typename Query, bool Robust, bool Counting, SingleStep Step, typename Tree, typename Answer>
void traceRange(const Tree& tree, std::span<const Ray> rays, const TraversalConfig& config, RayCoherence coherence,
                Answer&& answer) {
    const auto oneByOne = [&] {
        for (size_t i = 0; i < rays.size(); ++i) {
            QueryCounters work;
            const Query query = runQuery<Query, Robust, Counting, Step>(tree, rays[i], work);
            answer(i, query, work);
        }
    };
    if constexpr (std::is_same_v<Tree, BinaryBvh>) {
        oneByOne();
    } else {
        switch (batchPath<Query>(config, coherence)) {
            case BatchTraversal::Single:
                oneByOne();
                break;
            case BatchTraversal::Coherent:
                traceAsPackets<Counting, Query, Robust, PacketKind::Coherent>(tree, rays, config.packetFallback,
                                                                              answer);
                break;
            case BatchTraversal::Stream:
                traceAsStreams<Counting, Query, Robust>(tree, rays, answer);
                break;
            default:
                traceAsPackets<Counting, Query, Robust, PacketKind::Plain>(tree, rays, config.packetFallback, answer);
                break;
        }
    }
}

template <typename Tree, bool Robust, bool Counting, SingleStep Step>
void findNearestRange(const Tree& tree, std::span<const Ray> rays, std::span<Hit> hits, QueryCounters& counters,
                      std::span<RayCost> costs, const TraversalConfig& config, RayCoherence coherence) {
    traceRange<ClosestHitQuery, Robust, Counting, Step>(
        tree, rays, config, coherence, [&](size_t i, const ClosestHitQuery& query, const QueryCounters& work) {
            counters += work;
            Hit hit;
            answerOf(tree, query, hit);
            hits[i] = hit;
            if (!costs.empty()) costs[i] = Accelerator::costBetween({}, work);
        });
}

template <typename Tree, bool Robust, bool Counting, SingleStep Step>
void isOccludedRange(const Tree& tree, std::span<const Ray> rays, std::span<uint8_t> occluded, QueryCounters& counters,
                     std::span<RayCost> costs, const TraversalConfig& config, RayCoherence coherence) {
    traceRange<AnyHitQuery, Robust, Counting, Step>(tree, rays, config, coherence,
                                                    [&](size_t i, const AnyHitQuery& query, const QueryCounters& work) {
                                                        counters += work;
                                                        occluded[i] = query.occluded ? 1 : 0;
                                                        if (!costs.empty())
                                                            costs[i] = Accelerator::costBetween({}, work);
                                                    });
}

template <typename Tree, bool Robust, bool Counting, SingleStep Step>
constexpr typename TraversalKernels<Tree>::Queries kQueries{
    &findNearestKernel<Tree, Robust, Counting, Step>, &isOccludedKernel<Tree, Robust, Counting, Step>,
    &findNearestRange<Tree, Robust, Counting, Step>, &isOccludedRange<Tree, Robust, Counting, Step>};

template <typename Tree, bool Robust, SingleStep Step>
constexpr TraversalKernels<Tree> kKernels{BVHLAB_KERNEL_ISA, kQueries<Tree, Robust, true, Step>,
                                          kQueries<Tree, Robust, false, Step>};

template <typename Tree, SingleStep Step>
const TraversalKernels<Tree>& kernelsOf(bool robust) {
    return robust ? kKernels<Tree, true, Step> : kKernels<Tree, false, Step>;
}

}  // namespace
}  // namespace BVHLAB_KERNEL_NS

namespace kernels {

template <typename Tree>
const TraversalKernels<Tree>& BVHLAB_KERNEL_NS(bool robust, SingleStep step) {
    if constexpr (!std::is_same_v<Tree, BinaryBvh>) {
        if (step == SingleStep::Octant) return kernelsOf<Tree, SingleStep::Octant>(robust);
    }
    return kernelsOf<Tree, SingleStep::Offsets>(robust);
}

template const TraversalKernels<BinaryBvh>& BVHLAB_KERNEL_NS(bool, SingleStep);
template const TraversalKernels<WideBvh<4>>& BVHLAB_KERNEL_NS(bool, SingleStep);
template const TraversalKernels<WideBvh<8>>& BVHLAB_KERNEL_NS(bool, SingleStep);

}  // namespace kernels
}  // namespace bvhlab
