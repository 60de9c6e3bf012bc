// The ray-box tests of the BVH traversals: one box at a time for the binary layout, the N boxes
// of a wide node at once (SIMD layer) for the wide one. Both compute the same slab distances
// with the same operations in the same order, so they agree box for box.
//
// Robustness (Ize 2013, as in pbrt-v4): rounding in (bound - org) * invDir must never turn a
// grazing hit into a miss (a flat box, e.g. around an axis-aligned triangle, has equal near
// and far distances). So the far distances are pushed outwards by 2*gamma(4) of their
// magnitude, which covers four roundings: the subtraction, the product, 1/dir and the scaling.
// pbrt scales by 1 + 2*gamma, right only for far >= 0; that is all a ray with tmin >= 0 needs
// (a box with far < 0 lies behind it either way), and it is folded into a premultiplied 1/dir.
// Rays whose interval reaches below 0 (NegativeT) take the sign-aware form,
// far * (1 -+ 2*gamma). Robust = false (BVH::robust=false) drops the margin. (Embree's and
// tinybvh's fused form, bound * inv - org * inv, gives inf - inf = NaN for a zero direction
// component, and with it empty lanes that pass: it would need their safe reciprocal too.)
//
// Axis-parallel rays: 1/0 gives +-inf; when the origin lies exactly on a slab plane, 0 * inf is
// NaN. The min/max of the SIMD layer return their second argument when the first is NaN, so a
// NaN slab distance is dropped (the ray is inside that slab, which it is). Near and far slabs
// are chosen by the sign bit of invDir, so -0 directions are handled like -inf. The three axes
// are combined as a tree, max(max(x, y), max(z, tmin)), for a shorter dependency chain
// (measured 2-4 % faster); a NaN in y then drops x as well, which can only enlarge the box:
// never a missed hit. The entry distance itself is never NaN (tmin is not).
#pragma once

#include "accel/bvh/layout/bvh_node.h"
#include "accel/bvh/layout/wide_bvh.h"
#include "accel/bvh/simd/kernel_namespace.h"
#include "accel/bvh/simd/simd.h"

#include <cmath>
#include <cstddef>
#include <limits>

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {

// pbrt's gamma(n) = n*u/(1 - n*u), u = 2^-24: the bound on the relative error of n roundings.
constexpr float gammaBound(int n) {
    constexpr float u = std::numeric_limits<float>::epsilon() * 0.5f;
    return n * u / (1.0f - n * u);
}

// The fraction by which a robust box test pushes its far distances outwards (see above).
template <bool Robust>
inline constexpr float kFarMargin = Robust ? 2.0f * gammaBound(4) : 0.0f;

// What both tests precompute per ray: per axis the origin, 1/dir, 1/dir with the far margin
// folded in, and which bound (lower 0, upper 1) the ray crosses first.
template <bool Robust>
struct RaySlabs {
    float org[3];
    float inv[3];
    float invFar[3];  // inv * (1 + margin), for NegativeT = false
    int nearIsUpper[3];
    float tmin;

    [[gnu::always_inline]] explicit RaySlabs(const Ray& ray) : tmin(ray.tmin) {
        for (int a = 0; a < 3; ++a) {
            org[a] = ray.org[a];
            inv[a] = 1.0f / ray.dir[a];
            invFar[a] = inv[a] * (1.0f + kFarMargin<Robust>);
            nearIsUpper[a] = std::signbit(inv[a]) ? 1 : 0;
        }
    }

    // The ray's direction octant, as WideNode::order numbers them (directionOctant).
    int octant() const { return nearIsUpper[0] | nearIsUpper[1] << 1 | nearIsUpper[2] << 2; }

    // The near slab distance of `bound` on axis a: F is float (the binary test) or SIMD lanes
    // (the wide one).
    template <typename F>
    [[gnu::always_inline]] F nearDistance(F bound, int a) const {
        using simd::broadcast;
        return (bound - broadcast<F>(org[a])) * broadcast<F>(inv[a]);
    }

    // The far slab distance of `bound` on axis a, pushed outwards: F is float (the binary
    // test) or SIMD lanes (the wide one).
    template <bool NegativeT, typename F>
    [[gnu::always_inline]] F farDistance(F bound, int a) const {
        using simd::broadcast, simd::select;
        constexpr float margin = kFarMargin<Robust>;
        if constexpr (NegativeT && Robust) {
            // Scaled, not t + margin*|t|: an axis-parallel ray beside the slab gives t = -inf,
            // and -inf + inf would be a NaN that min drops (the box would not be culled).
            const F t = (bound - broadcast<F>(org[a])) * broadcast<F>(inv[a]);
            return t * select(t >= broadcast<F>(0.0f), broadcast<F>(1.0f + margin), broadcast<F>(1.0f - margin));
        } else {
            return (bound - broadcast<F>(org[a])) * broadcast<F>(invFar[a]);
        }
    }
};

// One binary node's box. Scalar on purpose: an SSE test of both children at once measured
// 40 % slower here. A step is bound by latency, and the SIMD version's longer chain resolved
// the branch later. Written out per axis in plain floats: the same test as a loop over
// simd::Scalar<1> measured 5-14 % slower on shadow rays (bench, 1 thread, 3 scenes).
template <bool NegativeT, bool Robust>
struct RayBoxTest : RaySlabs<Robust> {
    int nearSlab[3];  // index into BvhNode::bounds of the slab the ray enters first
    int farSlab[3];

    [[gnu::always_inline]] explicit RayBoxTest(const Ray& ray) : RaySlabs<Robust>(ray) {
        for (int a = 0; a < 3; ++a) {
            nearSlab[a] = a + 3 * this->nearIsUpper[a];
            farSlab[a] = a + 3 * (1 - this->nearIsUpper[a]);
        }
    }

    // True when the ray overlaps the box within [tmin, tmax]; `entry` is where it enters.
    [[gnu::always_inline]] bool intersect(const BvhNode& node, float tmax, float& entry) const {
        const float* b = node.bounds;
        const float nx = this->nearDistance(b[nearSlab[0]], 0);
        const float ny = this->nearDistance(b[nearSlab[1]], 1);
        const float nz = this->nearDistance(b[nearSlab[2]], 2);
        const float fx = this->template farDistance<NegativeT>(b[farSlab[0]], 0);
        const float fy = this->template farDistance<NegativeT>(b[farSlab[1]], 1);
        const float fz = this->template farDistance<NegativeT>(b[farSlab[2]], 2);
        entry = simd::max(simd::max(nx, ny), simd::max(nz, this->tmin));
        const float exit = simd::min(simd::min(fx, fy), simd::min(fz, tmax));
        return entry <= exit;
    }
};

// A ray's direction octant not known at compile time (WideBoxTest::test<Octant>).
inline constexpr int kAnyOctant = -1;

// The N child boxes of a wide node, in lanes of simd::Floats<N>. The ray's constants are kept
// as vectors for the whole traversal, so a node step loads the node and nothing else. Which
// bounds a ray enters first depends on its octant: test(node, tmax) finds them at byte offsets
// chosen per ray, test<Octant>(node, tmax) (the octant known at compile time, as tinybvh's
// BVH8_CPU) reads them as members at fixed offsets, which spares a step the offsets' registers
// or their reloads. Both perform the same operations on the same values.
template <int N, bool NegativeT, bool Robust>
struct WideBoxTest : RaySlabs<Robust> {
    using F = simd::Floats<N>;
    using Node = WideNode<N>;
    // Byte offsets into a node of the near and the far bounds of each axis.
    size_t nearOffset[3], farOffset[3];
    F org[3], inv[3], invFar[3], tmin;

    // Where the ray enters each child box, and the lanes whose box it overlaps.
    struct Hits {
        F entry;
        typename F::Mask mask;
    };

    [[gnu::always_inline]] explicit WideBoxTest(const Ray& ray) : RaySlabs<Robust>(ray) {
        for (int a = 0; a < 3; ++a) {
            const size_t lower = offsetof(Node, lower) + size_t(a) * sizeof(float) * N;
            const size_t upper = offsetof(Node, upper) + size_t(a) * sizeof(float) * N;
            nearOffset[a] = this->nearIsUpper[a] ? upper : lower;
            farOffset[a] = this->nearIsUpper[a] ? lower : upper;
            org[a] = F::broadcast(RaySlabs<Robust>::org[a]);
            inv[a] = F::broadcast(RaySlabs<Robust>::inv[a]);
            invFar[a] = F::broadcast(RaySlabs<Robust>::invFar[a]);
        }
        tmin = F::broadcast(RaySlabs<Robust>::tmin);
    }

    static const float* bounds(const Node& node, size_t offset) {
        return reinterpret_cast<const float*>(reinterpret_cast<const char*>(&node) + offset);
    }

    // RaySlabs::nearDistance's and farDistance's operations, on the constants in lanes.
    [[gnu::always_inline]] F nearDistance(F bound, int a) const { return (bound - org[a]) * inv[a]; }
    [[gnu::always_inline]] F farDistance(F bound, int a) const {
        if constexpr (NegativeT && Robust) {
            constexpr float margin = kFarMargin<Robust>;
            const F t = (bound - org[a]) * inv[a];
            return t * select(t >= F::broadcast(0.0f), F::broadcast(1.0f + margin), F::broadcast(1.0f - margin));
        } else {
            return (bound - org[a]) * invFar[a];
        }
    }

    // The boxes the ray overlaps within [tmin, tmax], given each axis's near and far bounds
    // loaded already: rays of one octant (stream_traversal.h) load a node's once for all.
    [[gnu::always_inline]] Hits test(const F nearBounds[3], const F farBounds[3], F tmax) const {
        F nearT[3], farT[3];
        for (int a = 0; a < 3; ++a) {
            nearT[a] = nearDistance(nearBounds[a], a);
            farT[a] = farDistance(farBounds[a], a);
        }
        const F entry = max(max(nearT[0], nearT[1]), max(nearT[2], tmin));
        const F exit = min(min(farT[0], farT[1]), min(farT[2], tmax));
        return {entry, entry <= exit};
    }

    // The same, each axis's near and far bounds read from where they lie.
    [[gnu::always_inline]] Hits test(const float* const (&nearBounds)[3], const float* const (&farBounds)[3],
                                     F tmax) const {
        const F nearLoaded[3] = {F::load(nearBounds[0]), F::load(nearBounds[1]), F::load(nearBounds[2])};
        const F farLoaded[3] = {F::load(farBounds[0]), F::load(farBounds[1]), F::load(farBounds[2])};
        return test(nearLoaded, farLoaded, tmax);
    }

    // The boxes of `node` the ray overlaps within [tmin, tmax], their bounds at the ray's offsets.
    [[gnu::always_inline]] Hits test(const Node& node, F tmax) const {
        const float* nearBounds[3] = {bounds(node, nearOffset[0]), bounds(node, nearOffset[1]),
                                      bounds(node, nearOffset[2])};
        const float* farBounds[3] = {bounds(node, farOffset[0]), bounds(node, farOffset[1]),
                                     bounds(node, farOffset[2])};
        return test(nearBounds, farBounds, tmax);
    }

    // The same for a ray of direction octant Octant (this ray's: octant(); kAnyOctant: the above).
    template <int Octant>
    [[gnu::always_inline]] Hits test(const Node& node, F tmax) const {
        if constexpr (Octant == kAnyOctant) {
            return test(node, tmax);
        } else {
            constexpr bool x = Octant & 1, y = Octant & 2, z = Octant & 4;
            const float* nearBounds[3] = {x ? node.upper[0] : node.lower[0], y ? node.upper[1] : node.lower[1],
                                          z ? node.upper[2] : node.lower[2]};
            const float* farBounds[3] = {x ? node.lower[0] : node.upper[0], y ? node.lower[1] : node.upper[1],
                                         z ? node.lower[2] : node.upper[2]};
            return test(nearBounds, farBounds, tmax);
        }
    }

    // The same as a bit mask, where the ray enters each box to entryOut.
    [[gnu::always_inline]] int intersect(const Node& node, float tmax, float entryOut[N]) const {
        const Hits hits = test(node, F::broadcast(tmax));
        hits.entry.storeu(entryOut);
        return movemask(hits.mask);
    }
};

}  // namespace BVHLAB_KERNEL_NS
}  // namespace bvhlab
