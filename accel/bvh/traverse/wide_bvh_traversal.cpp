#include "accel/bvh/traverse/wide_bvh_traversal.h"

#include "accel/bvh/simd/bvh_simd.h"
#include "accel/bvh/traverse/traversal_common.h"

#include <cmath>
#include <cstddef>

namespace bvhlab {
namespace {

constexpr int kWidth = WideNode::kWidth;

// The four child boxes of a node against the ray: the lanes whose box the ray overlaps
// within [tmin, tmax] as a bit mask, and where it enters each. Lane by lane the operations
// of the binary traversal's RayBoxTest (see bvh_traversal.cpp for the robustness argument):
// SSE's maxps/minps are exactly its robustMax/robustMin (a > b ? a : b, the second operand
// on NaN), so the scalar twin and the SSE path give the same answers.
template <bool NegativeT, bool Robust>
struct WideBoxTest {
    static constexpr float kMargin = kFarMargin<Robust>;
    // Byte offsets into a WideNode of the near and the far bounds of each axis, chosen by the
    // sign of 1/dir (so that -0 directions count as negative, as in the binary test).
    size_t nearOffset[3], farOffset[3];
    float org[3], inv[3], invFar[3], tmin;

    explicit WideBoxTest(const Ray& ray) : tmin(ray.tmin) {
        for (int a = 0; a < 3; ++a) {
            org[a] = ray.org[a];
            inv[a] = 1.0f / ray.dir[a];
            invFar[a] = inv[a] * (1.0f + kMargin);
            const size_t lower = offsetof(WideNode, lower) + size_t(a) * sizeof(float) * kWidth;
            const size_t upper = offsetof(WideNode, upper) + size_t(a) * sizeof(float) * kWidth;
            const bool negative = std::signbit(inv[a]);
            nearOffset[a] = negative ? upper : lower;
            farOffset[a] = negative ? lower : upper;
        }
    }

    static const float* bounds(const WideNode& node, size_t offset) {
        return reinterpret_cast<const float*>(reinterpret_cast<const char*>(&node) + offset);
    }

#if BVHLAB_BVH_SSE
    int intersect(const WideNode& node, float tmax, float entryOut[kWidth]) const {
        __m128 nearT[3], farT[3];
        for (int a = 0; a < 3; ++a) {
            const __m128 o = _mm_set1_ps(org[a]);
            nearT[a] = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(bounds(node, nearOffset[a])), o), _mm_set1_ps(inv[a]));
            const __m128 farDiff = _mm_sub_ps(_mm_load_ps(bounds(node, farOffset[a])), o);
            if constexpr (NegativeT && Robust) {
                // t * (1 + margin) where t >= 0, t * (1 - margin) below: outwards either way.
                const __m128 t = _mm_mul_ps(farDiff, _mm_set1_ps(inv[a]));
                const __m128 up = _mm_cmpge_ps(t, _mm_setzero_ps());
                const __m128 scale = _mm_or_ps(_mm_and_ps(up, _mm_set1_ps(1.0f + kMargin)),
                                               _mm_andnot_ps(up, _mm_set1_ps(1.0f - kMargin)));
                farT[a] = _mm_mul_ps(t, scale);
            } else {
                farT[a] = _mm_mul_ps(farDiff, _mm_set1_ps(invFar[a]));
            }
        }
        const __m128 entry = _mm_max_ps(_mm_max_ps(nearT[0], nearT[1]), _mm_max_ps(nearT[2], _mm_set1_ps(tmin)));
        const __m128 exit = _mm_min_ps(_mm_min_ps(farT[0], farT[1]), _mm_min_ps(farT[2], _mm_set1_ps(tmax)));
        _mm_storeu_ps(entryOut, entry);
        return _mm_movemask_ps(_mm_cmple_ps(entry, exit));
    }
#else
    int intersect(const WideNode& node, float tmax, float entryOut[kWidth]) const {
        auto maxOf = [](float a, float b) { return a > b ? a : b; };
        auto minOf = [](float a, float b) { return a < b ? a : b; };
        int mask = 0;
        for (int i = 0; i < kWidth; ++i) {
            float nearT[3], farT[3];
            for (int a = 0; a < 3; ++a) {
                nearT[a] = (bounds(node, nearOffset[a])[i] - org[a]) * inv[a];
                const float farDiff = bounds(node, farOffset[a])[i] - org[a];
                if constexpr (NegativeT && Robust) {
                    const float t = farDiff * inv[a];
                    farT[a] = t * (t >= 0.0f ? 1.0f + kMargin : 1.0f - kMargin);
                } else {
                    farT[a] = farDiff * invFar[a];
                }
            }
            const float entry = maxOf(maxOf(nearT[0], nearT[1]), maxOf(nearT[2], tmin));
            const float exit = minOf(minOf(farT[0], farT[1]), minOf(farT[2], tmax));
            entryOut[i] = entry;
            mask |= int(entry <= exit) << i;
        }
        return mask;
    }
#endif
};

// A child to visit: a wide node (count 0) or a leaf, and where the ray enters its box.
struct StackEntry {
    uint32_t child;
    uint32_t count;
    float entry;
};

// Each step pops one entry and pushes at most four: the stack never holds more than three
// per level plus one.
constexpr int kStackSize = 3 * kBvhMaxDepth + 1;

// The next child to visit among the lanes in `mask` (not 0): the nearest. The others are
// pushed far to near, so that the next nearest is popped first; what they will read starts
// loading now.
inline StackEntry nextChild(const WideNode& node, int mask, const float entry[kWidth], StackEntry* stack, int& size,
                            const WideNode* nodes, const Triangle* triangles) {
    const int first = __builtin_ctz(unsigned(mask));
    mask &= mask - 1;
    StackEntry nearest{node.child[first], node.count[first], entry[first]};
    if (mask == 0) return nearest;  // the common case: one child hit
    StackEntry hits[kWidth];
    int k = 0;
    hits[k++] = nearest;
    while (mask != 0) {
        const int i = __builtin_ctz(unsigned(mask));
        mask &= mask - 1;
        const StackEntry e{node.child[i], node.count[i], entry[i]};
        int j = k++;
        for (; j > 0 && hits[j - 1].entry < e.entry; --j) hits[j] = hits[j - 1];
        hits[j] = e;
    }
    for (int i = 0; i < k - 1; ++i) {
        const StackEntry& e = hits[i];
        __builtin_prefetch(e.count != 0 ? static_cast<const void*>(triangles + e.child)
                                        : static_cast<const void*>(nodes + e.child));
        stack[size++] = e;
    }
    return hits[k - 1];
}

template <bool NegativeT, bool Robust>
bool findNearest(const WideBvh& bvh, const Ray& ray, Hit& hit, QueryCounters& counters) {
    const WideBoxTest<NegativeT, Robust> boxTest(ray);
    const LeafTriangleTest<Robust> intersectTriangle(ray);
    const WideNode* nodes = bvh.nodes.data();
    const Triangle* triangles = bvh.leafTriangles.data();

    float tmax = ray.tmax;
    uint32_t found = kInvalidPrimitive;  // position in leaf order of the closest hit so far
    TriangleHitT<float> best{};
    uint64_t steps = 0, tests = 0;

    StackEntry stack[kStackSize];
    int size = 0;
    StackEntry current{0, 0, ray.tmin};  // the root
    for (;;) {
        ++steps;
        if (current.count == 0) {
            const WideNode& node = nodes[current.child];
            float entry[kWidth];
            const int mask = boxTest.intersect(node, tmax, entry);
            if (mask != 0) {
                current = nextChild(node, mask, entry, stack, size, nodes, triangles);
                continue;
            }
        } else {
            tests += current.count;
            for (uint32_t i = current.child, end = current.child + current.count; i < end; ++i) {
                TriangleHitT<float> h;
                if (intersectTriangle(triangles[i], ray.tmin, tmax, h)) {
                    tmax = h.t;
                    best = h;
                    found = i;
                }
            }
        }
        // Pop the next child the ray enters before the closest hit so far.
        while (size > 0 && stack[size - 1].entry > tmax) --size;
        if (size == 0) break;
        current = stack[--size];
    }
    counters.traversalSteps += steps;
    counters.intersectionTests += tests;
    if (found == kInvalidPrimitive) return false;
    hit = {best.t, bvh.primIndices[found], best.u, best.v};
    return true;
}

template <bool NegativeT, bool Robust>
bool isOccluded(const WideBvh& bvh, const Ray& ray, QueryCounters& counters) {
    const WideBoxTest<NegativeT, Robust> boxTest(ray);
    const LeafTriangleTest<Robust> intersectTriangle(ray);
    const WideNode* nodes = bvh.nodes.data();
    const Triangle* triangles = bvh.leafTriangles.data();
    const float tmax = ray.tmax;

    uint64_t steps = 0, tests = 0;
    bool occluded = false;
    StackEntry stack[kStackSize];
    int size = 0;
    StackEntry current{0, 0, ray.tmin};  // the root
    for (;;) {
        ++steps;
        if (current.count == 0) {
            const WideNode& node = nodes[current.child];
            float entry[kWidth];
            const int mask = boxTest.intersect(node, tmax, entry);
            if (mask != 0) {
                // Nearer first here too: an occluder near the origin is found sooner.
                current = nextChild(node, mask, entry, stack, size, nodes, triangles);
                continue;
            }
        } else {
            for (uint32_t i = current.child, end = current.child + current.count; i < end; ++i) {
                ++tests;
                TriangleHitT<float> h;
                if (intersectTriangle(triangles[i], ray.tmin, tmax, h)) {
                    occluded = true;
                    break;
                }
            }
            if (occluded) break;
        }
        if (size == 0) break;
        current = stack[--size];
    }
    counters.traversalSteps += steps;
    counters.intersectionTests += tests;
    return occluded;
}

}  // namespace

bool wideBvhFindNearest(const WideBvh& bvh, const Ray& ray, Hit& hit, QueryCounters& counters, bool robust) {
    return runQuery(bvh, ray, robust, counters,
                    [&](auto negT, auto robT) { return findNearest<negT(), robT()>(bvh, ray, hit, counters); });
}

bool wideBvhIsOccluded(const WideBvh& bvh, const Ray& ray, QueryCounters& counters, bool robust) {
    return runQuery(bvh, ray, robust, counters,
                    [&](auto negT, auto robT) { return isOccluded<negT(), robT()>(bvh, ray, counters); });
}

}  // namespace bvhlab
