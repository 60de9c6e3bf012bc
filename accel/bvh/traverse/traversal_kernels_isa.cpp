// One ISA's traversal kernels (traversal_kernels.h): compiled once per ISA with its -march and
// -DBVHLAB_KERNEL_NS=<isa> -DBVHLAB_KERNEL_ISA=Isa::<Isa> (accel/CMakeLists.txt), so that all it
// instantiates lives in namespace bvhlab::<isa> (kernel_namespace.h) and the table it exports is
// kernels::<isa>. The entry points themselves have internal linkage.
#include "accel/bvh/traverse/traversal_kernels.h"
#include "accel/bvh/traverse/bvh_traversal.h"
#include "accel/bvh/traverse/wide_bvh_traversal.h"

#ifndef BVHLAB_KERNEL_ISA
#error "compiled per ISA only: accel/CMakeLists.txt defines BVHLAB_KERNEL_NS and BVHLAB_KERNEL_ISA"
#endif

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {
namespace {

template <typename Tree, bool Robust>
bool findNearestKernel(const Tree& tree, const Ray& ray, Hit& hit, QueryCounters& counters) {
    return answerOf(tree, runQuery<ClosestHitQuery, Robust>(tree, ray, counters), hit);
}

template <typename Tree, bool Robust>
bool isOccludedKernel(const Tree& tree, const Ray& ray, QueryCounters& counters) {
    return runQuery<AnyHitQuery, Robust>(tree, ray, counters).occluded;
}

template <typename Tree, bool Robust>
void findNearestRange(const Tree& tree, std::span<const Ray> rays, std::span<Hit> hits, QueryCounters& counters,
                      std::span<RayCost> costs) {
    for (size_t i = 0; i < rays.size(); ++i) {
        const QueryCounters before = counters;
        Hit hit;
        answerOf(tree, runQuery<ClosestHitQuery, Robust>(tree, rays[i], counters), hit);
        hits[i] = hit;
        if (!costs.empty()) costs[i] = Accelerator::costBetween(before, counters);
    }
}

template <typename Tree, bool Robust>
void isOccludedRange(const Tree& tree, std::span<const Ray> rays, std::span<uint8_t> occluded, QueryCounters& counters,
                     std::span<RayCost> costs) {
    for (size_t i = 0; i < rays.size(); ++i) {
        const QueryCounters before = counters;
        occluded[i] = runQuery<AnyHitQuery, Robust>(tree, rays[i], counters).occluded ? 1 : 0;
        if (!costs.empty()) costs[i] = Accelerator::costBetween(before, counters);
    }
}

template <typename Tree, bool Robust>
constexpr TraversalKernels<Tree> kKernels{BVHLAB_KERNEL_ISA, &findNearestKernel<Tree, Robust>,
                                          &isOccludedKernel<Tree, Robust>, &findNearestRange<Tree, Robust>,
                                          &isOccludedRange<Tree, Robust>};

}  // namespace
}  // namespace BVHLAB_KERNEL_NS

namespace kernels {

template <typename Tree>
const TraversalKernels<Tree>& BVHLAB_KERNEL_NS(bool robust) {
    return robust ? kKernels<Tree, true> : kKernels<Tree, false>;
}

template const TraversalKernels<Bvh>& BVHLAB_KERNEL_NS(bool);
template const TraversalKernels<WideBvh<4>>& BVHLAB_KERNEL_NS(bool);
template const TraversalKernels<WideBvh<8>>& BVHLAB_KERNEL_NS(bool);

}  // namespace kernels
}  // namespace bvhlab
