// The namespace of the SIMD kernels' code. The traversal is compiled once per ISA
// (accel/bvh/traverse/traversal_kernels_isa.cpp; accel/CMakeLists.txt), and the templates and
// inline functions of the SIMD layer, the box and triangle tests and the skeletons would then
// exist in several objects under one name: the linker keeps one copy of each, maybe an AVX-512
// one that an AVX2 machine cannot run. So all of them live in an inline namespace named per
// compilation (-DBVHLAB_KERNEL_NS=avx2): bvhlab::avx2::simd::Avx is another symbol than
// bvhlab::avx512::simd::Avx, and code that does not care still writes bvhlab::simd::Avx.
// Everything else (the builders, the accelerator, the tests) compiles it as bvhlab::native.
#pragma once

#ifndef BVHLAB_KERNEL_NS
#define BVHLAB_KERNEL_NS native
#endif
