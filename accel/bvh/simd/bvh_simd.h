// SIMD for the BVH build and traversal: SSE2, which every x86-64 CPU has. Code using it sits
// behind BVHLAB_BVH_SSE and has a scalar twin, so that other targets still build.
#pragma once

#if defined(__SSE2__)
#include <immintrin.h>
#define BVHLAB_BVH_SSE 1
#else
#define BVHLAB_BVH_SSE 0
#endif
