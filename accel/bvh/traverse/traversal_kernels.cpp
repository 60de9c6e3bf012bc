#include "accel/bvh/traverse/traversal_kernels.h"

#include "framework/core/cpu_levels.h"
#include "framework/core/error.h"

#include <fmt/format.h>

namespace bvhlab {

// The words of the BVH:: keys (traversal_config.h), literals: each ends in a NUL.
const char* isaName(Isa isa) { return kIsaWords[size_t(isa)].data(); }
const char* batchTraversalName(BatchTraversal path) { return kBatchTraversalWords[size_t(path)].data(); }
const char* singleStepName(SingleStep step) { return kSingleStepWords[size_t(step)].data(); }

int isaVectorBits(Isa isa) {
    switch (isa) {
        case Isa::Auto:
            return 0;
        case Isa::Scalar:
            return 128;
        case Isa::Avx2:
            return 256;
        case Isa::Avx512:
            return 512;
    }
    return 0;
}

// The kernels are compiled for the x86-64 micro-architecture levels (accel/CMakeLists.txt):
// the baseline, v3 and v4 (framework/core/cpu_levels.h).
bool cpuRuns(Isa isa) {
    const CpuLevels cpu = cpuLevels();
    switch (isa) {
        case Isa::Auto:
        case Isa::Scalar:
            return true;
        case Isa::Avx2:
            return cpu.v3;
        case Isa::Avx512:
            return cpu.v4;
    }
    return false;
}

Isa bestIsa() {
    for (Isa isa : {Isa::Avx512, Isa::Avx2})
        if (cpuRuns(isa)) return isa;
    return Isa::Scalar;
}

template <typename Tree>
TraversalKernels<Tree> traversalKernels(const TraversalConfig& config) {
    const Isa isa = config.isa == Isa::Auto ? bestIsa() : config.isa;
    if (!cpuRuns(isa))
        throw InputError(fmt::format("BVH::isa={}: this CPU does not run the {} kernels (it runs up to {})",
                                     isaName(isa), isaName(isa), isaName(bestIsa())));
    switch (isa) {
        case Isa::Avx512:
            return kernels::avx512<Tree>(config.robust, config.singleStep);
        case Isa::Avx2:
            return kernels::avx2<Tree>(config.robust, config.singleStep);
        default:
            return kernels::scalar<Tree>(config.robust, config.singleStep);
    }
}

template TraversalKernels<BinaryBvh> traversalKernels(const TraversalConfig&);
template TraversalKernels<WideBvh<4>> traversalKernels(const TraversalConfig&);
template TraversalKernels<WideBvh<8>> traversalKernels(const TraversalConfig&);

}  // namespace bvhlab
