#include "accel/bvh/traverse/traversal_kernels.h"

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
    case BatchTraversal::Single: return "single";
    case BatchTraversal::Stream: return "stream";
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
// the baseline, v3 (AVX2, FMA, BMI1/2, and LZCNT, MOVBE, F16C, which every CPU with those has)
// and v4 (v3 and AVX-512 F/BW/CD/DQ/VL). Checked feature by feature: clang's check does not
// know the level names.
bool cpuRuns(Isa isa) {
    __builtin_cpu_init();
    const bool v3 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                    __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2");
    const bool v4 = v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                    __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
                    __builtin_cpu_supports("avx512vl");
    switch (isa) {
    case Isa::Auto:
    case Isa::Scalar: return true;
    case Isa::Avx2: return v3;
    case Isa::Avx512: return v4;
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
    case Isa::Avx512: return kernels::avx512<Tree>(config.robust);
    case Isa::Avx2: return kernels::avx2<Tree>(config.robust);
    default: return kernels::scalar<Tree>(config.robust);
    }
}

template TraversalKernels<BinaryBvh> traversalKernels(const TraversalConfig&);
template TraversalKernels<WideBvh<4>> traversalKernels(const TraversalConfig&);
template TraversalKernels<WideBvh<8>> traversalKernels(const TraversalConfig&);

}  // namespace bvhlab
