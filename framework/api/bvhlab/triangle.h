// The one ray-triangle test all of our accelerators share: the watertight test of
// Woop, Benthin and Wald (JCGT 2013). The ray is sheared so that it runs along +z from
// the origin; the three 2D edge functions then decide inside/outside with consistent
// rounding along shared edges, so a ray cannot slip between two adjacent triangles.
#pragma once

#include <bvhlab/ray.h>

namespace bvhlab {

struct Triangle {
    Vec3 v0, v1, v2;

    Bounds3 bounds() const {
        Bounds3 b(v0);
        b.extend(v1);
        b.extend(v2);
        return b;
    }
    Vec3 centroid() const { return (v0 + v1 + v2) * (1.0f / 3.0f); }
    Vec3 geometricNormal() const { return math::cross(v1 - v0, v2 - v0); }
};

// Per-ray precomputation of the shear (done once per query, not per triangle).
template <typename Real>
struct ShearedRayT {
    using V = glm::vec<3, Real>;
    V org;
    int kx, ky, kz;
    Real sx, sy, sz;

    // Always inlined: the traversal kernels, compiled once per ISA (accel/bvh/traverse/
    // traversal_kernels.h), must not leave a copy of their own that the linker could pick.
    // The direction is read from an array by the axes found: glm's vector indexed by a run-time
    // axis compiles to a branch per read.
    [[gnu::always_inline]] explicit ShearedRayT(const Ray& ray) : org(ray.org) {
        const Real dir[3] = {Real(ray.dir.x), Real(ray.dir.y), Real(ray.dir.z)};
        const Real ax = math::abs(dir[0]), ay = math::abs(dir[1]), az = math::abs(dir[2]);
        kz = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
        const int x = kz == 2 ? 0 : kz + 1, y = x == 2 ? 0 : x + 1;
        const bool flip = dir[kz] < Real(0);  // keep the winding of the 2D projection
        kx = flip ? y : x;
        ky = flip ? x : y;
        sx = dir[kx] / dir[kz];
        sy = dir[ky] / dir[kz];
        sz = Real(1) / dir[kz];
    }
};
using ShearedRay = ShearedRayT<float>;

// Result of one ray-triangle test; u, v follow the Hit convention (weights of v1 and v2).
template <typename Real>
struct TriangleHitT {
    Real t, u, v;
};

// The edge function a*b - c*d of the watertight test. Watertightness needs its sign exact
// (and 0 only when the exact value is 0): then a shared edge gives opposite signs in the two
// triangles that share it, and the spokes of a vertex's fan cannot all fall on one side of
// the ray. Rounded float products do not give that: edge functions in plain float leaked
// 1 in 1e6 edge probes on a10, rays slipping through a fan whose spokes all rounded the same
// way. (A compiler's contraction of a*b - c*d into one fma is as bad: -ffp-contract=off.)
//
// So float takes a filtered path (Shewchuk's static filter; Woop et al. 2013 fall back only on
// an exact 0, which is not enough): e = fma(a, b, -fl(c*d)) carries two roundings, of c*d and
// of the result, so |e - (ab - cd)| <= u|c*d| + u|e| + a tiny absolute term where products
// are subnormal or flushed to 0. Where |e| exceeds kEdgeErrorScale*|fl(c*d)| + kEdgeErrorFloor
// (2u plus margin for the bound's own rounding) its sign is the exact one; elsewhere (and on
// NaN or overflow) e is recomputed in double, where both products are exact (24 + 24 bits <
// 53): that sign is exact. The SIMD block test (accel/bvh/traverse/triangle_block_test.h)
// computes the same, lane for lane. double, the oracle's reference, forms both products in
// long double, rounded alike whatever the compiler contracts (x87 has no fma), so that
// e(a, b, c, d) == -e(c, d, a, b) exactly and coincident vertices give exactly 0.
inline constexpr float kEdgeErrorScale = 0x1p-22f;
inline constexpr float kEdgeErrorFloor = 0x1p-124f;

inline float edgeFunction(float a, float b, float c, float d) {
    const float cd = c * d;
    const float e = math::fma(a, b, -cd);
    if (math::abs(e) > math::fma(math::abs(cd), kEdgeErrorScale, kEdgeErrorFloor)) return e;
    return float(double(a) * double(b) - double(c) * double(d));
}

inline double edgeFunction(double a, double b, double c, double d) {
    using Wide = long double;
    return double(Wide(a) * Wide(b) - Wide(c) * Wide(d));
}

// Returns true and fills `out` when the ray hits the triangle at t in [tmin, tmax].
// Real = double gives the reference used by the oracle tests.
template <typename Real>
inline bool intersectTriangle(const ShearedRayT<Real>& r, const Triangle& tri, Real tmin, Real tmax,
                              TriangleHitT<Real>& out) {
    using V = glm::vec<3, Real>;
    const V a = V(tri.v0) - r.org;
    const V b = V(tri.v1) - r.org;
    const V c = V(tri.v2) - r.org;
    const Real ax = a[r.kx] - r.sx * a[r.kz], ay = a[r.ky] - r.sy * a[r.kz];
    const Real bx = b[r.kx] - r.sx * b[r.kz], by = b[r.ky] - r.sy * b[r.kz];
    const Real cx = c[r.kx] - r.sx * c[r.kz], cy = c[r.ky] - r.sy * c[r.kz];

    // Edge functions (2D cross products) with exact signs (edgeFunction above).
    const Real e0 = edgeFunction(cx, by, cy, bx);  // edge v1-v2: weight of v0
    const Real e1 = edgeFunction(ax, cy, ay, cx);  // edge v2-v0: weight of v1
    const Real e2 = edgeFunction(bx, ay, by, ax);  // edge v0-v1: weight of v2
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return false;
    const Real det = e0 + e1 + e2;
    if (det == Real(0)) return false;

    const Real az = r.sz * a[r.kz], bz = r.sz * b[r.kz], cz = r.sz * c[r.kz];
    const Real invDet = Real(1) / det;
    const Real t = (e0 * az + e1 * bz + e2 * cz) * invDet;
    if (!(t >= tmin && t <= tmax)) return false;
    out = {t, e1 * invDet, e2 * invDet};
    return true;
}

}  // namespace bvhlab
