// What the binary and the 4-wide BVH traversals share: the error bound behind the box test's
// far-plane margin, and the leaves' triangle test.
#pragma once

#include "framework/core/triangle.h"
#include "framework/core/triangle_moller_trumbore.h"

#include <limits>
#include <type_traits>

namespace bvhlab {

// pbrt's gamma(n) = n*u/(1 - n*u), u = 2^-24: the bound on the relative error of n roundings.
constexpr float gammaBound(int n) {
    constexpr float u = std::numeric_limits<float>::epsilon() * 0.5f;
    return n * u / (1.0f - n * u);
}

// The far distances of a robust box test are pushed outwards by this fraction of their
// magnitude: it covers four roundings (the subtraction, the product, 1/dir, the scaling).
template <bool Robust>
inline constexpr float kFarMargin = Robust ? 2.0f * gammaBound(4) : 0.0f;

// The leaves' triangle test: the shared watertight one, or Moeller-Trumbore when robustness
// is switched off (BVH::robust=false).
template <bool Robust>
struct LeafTriangleTest {
    ShearedRay sheared;
    explicit LeafTriangleTest(const Ray& ray) : sheared(ray) {}
    bool operator()(const Triangle& tri, float tmin, float tmax, TriangleHitT<float>& h) const {
        return intersectTriangle(sheared, tri, tmin, tmax, h);
    }
};
template <>
struct LeafTriangleTest<false> {
    const Ray& ray;
    explicit LeafTriangleTest(const Ray& ray) : ray(ray) {}
    bool operator()(const Triangle& tri, float tmin, float tmax, TriangleHitT<float>& h) const {
        return intersectTriangleMollerTrumbore(ray, tri, tmin, tmax, h);
    }
};

// The entry of every query: it counts, answers invalid rays and empty trees with a miss, and
// runs `query(negativeT, robust)` with the traversal variant the ray needs, both passed as
// std::bool_constant: negativeT when the interval reaches below t = 0 (the box test's far
// margin must then be sign-aware), robust per BVH::robust.
template <typename Tree, typename Query>
bool runQuery(const Tree& tree, const Ray& ray, bool robust, QueryCounters& counters, Query&& query) {
    ++counters.queries;
    if (tree.empty() || !ray.isValid()) return false;
    using Yes = std::true_type;
    using No = std::false_type;
    if (robust) return ray.tmin < 0.0f ? query(Yes{}, Yes{}) : query(No{}, Yes{});
    return ray.tmin < 0.0f ? query(Yes{}, No{}) : query(No{}, No{});
}

}  // namespace bvhlab
