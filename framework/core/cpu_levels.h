// The x86-64 micro-architecture levels this CPU runs: what SIMD kernels compiled for them need
// (ours, BVH::isa; Embree's, Embree::isa).
#pragma once

namespace bvhlab {

struct CpuLevels {
    bool v3 = false;  // AVX2, FMA, BMI1/2 (and LZCNT, MOVBE, F16C, which every CPU with those has)
    bool v4 = false;  // v3 and AVX-512 F/BW/CD/DQ/VL
};

CpuLevels cpuLevels();

}  // namespace bvhlab
