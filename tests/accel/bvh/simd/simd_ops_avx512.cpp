// simd_ops.h on the AVX-512 backend: compiled for x86-64-v4 in namespace bvhlab::avx512
// (tests/CMakeLists.txt), called by test_simd.cpp only where the CPU runs it.
#include "tests/accel/bvh/simd/simd_ops.h"

namespace bvhlab::test {

void avx512SimdOpResults(const float* a, const float* b, const float* c, uint32_t* out) {
    simdOpResults<simd::Avx512>(a, b, c, out);
}

}  // namespace bvhlab::test
