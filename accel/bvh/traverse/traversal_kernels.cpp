#include "accel/bvh/traverse/traversal_kernels.h"

#include "framework/core/cpu_levels.h"
#include "framework/core/error.h"

#include <fmt/format.h>

namespace bvhlab {

const char* isaName(Isa isa) {
    switch (isa) {
    case Isa::Auto: return "auto";
    case Isa::Scalar: return "scalar";
    case Isa::Avx2: return "avx2";
    case Isa::Avx512: return "avx512";
    }
    return "?";
}

const char* batchTraversalName(BatchTraversal path) {
    switch (path) {
    case BatchTraversal::Auto: return "auto";
    case BatchTraversal::Packets: return "packets";
    case BatchTraversal::Coherent: return "coherent";
    case BatchTraversal::Single: return "single";
    case BatchTraversal::Stream: return "stream";
    }
    return "?";
}

const char* singleStepName(SingleStep step) {
    switch (step) {
    case SingleStep::Offsets: return "offsets";
    case SingleStep::Octant: return "octant";
    }
    return "?";
}

int isaVectorBits(Isa isa) {
    switch (isa) {
    case Isa::Auto: return 0;
    case Isa::Scalar: return 128;
    case Isa::Avx2: return 256;
    case Isa::Avx512: return 512;
    }
    return 0;
}

// The kernels are compiled for the x86-64 micro-architecture levels (accel/CMakeLists.txt):
// the baseline, v3 and v4 (framework/core/cpu_levels.h).
bool cpuRuns(Isa isa) {
    const CpuLevels cpu = cpuLevels();
    switch (isa) {
    case Isa::Auto:
    case Isa::Scalar: return true;
    case Isa::Avx2: return cpu.v3;
    case Isa::Avx512: return cpu.v4;
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
    case Isa::Avx512: return kernels::avx512<Tree>(config.robust, config.singleStep);
    case Isa::Avx2: return kernels::avx2<Tree>(config.robust, config.singleStep);
    default: return kernels::scalar<Tree>(config.robust, config.singleStep);
    }
}

template TraversalKernels<BinaryBvh> traversalKernels(const TraversalConfig&);
template TraversalKernels<WideBvh<4>> traversalKernels(const TraversalConfig&);
template TraversalKernels<WideBvh<8>> traversalKernels(const TraversalConfig&);

}  // namespace bvhlab
