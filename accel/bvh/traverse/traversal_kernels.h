// The traversal kernels: the query entry points of every layout (binary_bvh_traversal.h,
// wide_bvh_traversal.h), compiled once per ISA (traversal_kernels_isa.cpp, accel/CMakeLists.txt)
// and chosen at run time, as Embree does, so that one binary runs the SIMD code of the machine
// it runs on:
//   scalar  the x86-64 baseline (SSE2: Floats<4> is Sse, Floats<8> and Floats<16> plain C++);
//   avx2    x86-64-v3 (AVX2 and FMA: Floats<8> is Avx);
//   avx512  x86-64-v4 (AVX-512 F/DQ/BW/VL: Floats<16> is Avx512 as well).
// Every kernel answers bit for bit alike, with the same counters (the SIMD layer's guarantee;
// a test runs them side by side). A table is picked once per accelerator, with the robustness
// setting folded in: a query is one indirect call, no test of the setting.
#pragma once

#include "accel/bvh/layout/binary_bvh.h"
#include "accel/bvh/layout/wide_bvh.h"
#include "accel/bvh/traverse/traversal_config.h"
#include "framework/core/accelerator.h"

#include <span>
#include <string>

namespace bvhlab {

// The triangle tree's part of the accelerator's queries, for one layout (Tree: BinaryBvh or
// WideBvh<N>), in two forms compiled apart: one counts N_IT and N_TR, the other counts
// nothing but the queries and is what a timed query runs (QueryCounters::counting picks one).
// The batch calls take rays one by one (or as the kernel packs them) with the Accelerator's
// contract: misses as Hit(), costs filled when not empty (and counted). The wide layouts trace a
// batch by its path (packets, streams, single rays), the binary one ray by ray.
template <typename Tree>
struct TraversalKernels {
    struct Queries {
        bool (*findNearest)(const Tree& tree, const Ray& ray, Hit& hit, QueryCounters& counters);
        bool (*isOccluded)(const Tree& tree, const Ray& ray, QueryCounters& counters);
        // `config` chooses the wide layouts' batch path (BVH::batchTraversal, with `coherence`
        // when Auto) and its settings.
        void (*findNearestBatch)(const Tree& tree, std::span<const Ray> rays, std::span<Hit> hits,
                                 QueryCounters& counters, std::span<RayCost> costs, const TraversalConfig& config,
                                 RayCoherence coherence);
        void (*isOccludedBatch)(const Tree& tree, std::span<const Ray> rays, std::span<uint8_t> occluded,
                                QueryCounters& counters, std::span<RayCost> costs, const TraversalConfig& config,
                                RayCoherence coherence);
    };
    Isa isa;
    Queries counting;
    Queries timed;

    // The form `counters` asks for; a batch with costs to fill counts.
    const Queries& forCounters(const QueryCounters& counters, bool costs = false) const {
        return counters.counting || costs ? counting : timed;
    }
};

// The kernels of `config` (its robustness, its single-ray step, its ISA: Auto = the best this CPU runs). Throws
// InputError naming BVH::isa when the CPU cannot run the ISA asked for.
template <typename Tree>
TraversalKernels<Tree> traversalKernels(const TraversalConfig& config);

// Whether this CPU runs the kernels of `isa` (Auto: always).
bool cpuRuns(Isa isa);
// The best ISA this CPU runs (never Auto).
Isa bestIsa();
// "scalar", "avx2", "avx512" ("auto" for Auto): BVH::isa's values.
const char* isaName(Isa isa);
// "auto", "packets", "coherent", "stream", "single": BVH::batchTraversal's values.
const char* batchTraversalName(BatchTraversal path);
// "offsets", "octant": BVH::singleStep's values.
const char* singleStepName(SingleStep step);
// The widest vectors the kernels of `isa` use, in bits: 128 (SSE2), 256, 512 (0 for Auto).
int isaVectorBits(Isa isa);

// One table per ISA, each defined by that ISA's compilation of traversal_kernels_isa.cpp (the
// binary layout has one single-ray step, whatever `step` says).
namespace kernels {
template <typename Tree>
const TraversalKernels<Tree>& scalar(bool robust, SingleStep step);
template <typename Tree>
const TraversalKernels<Tree>& avx2(bool robust, SingleStep step);
template <typename Tree>
const TraversalKernels<Tree>& avx512(bool robust, SingleStep step);
}  // namespace kernels

}  // namespace bvhlab
