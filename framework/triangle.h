// The one ray-triangle test all of our accelerators share: the watertight test of
// Woop, Benthin and Wald (JCGT 2013). The ray is sheared so that it runs along +z from
// the origin; the three 2D edge functions then decide inside/outside with consistent
// rounding along shared edges, so a ray cannot slip between two adjacent triangles.
#pragma once

#include "framework/ray.h"

#include <cmath>
#include <type_traits>

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
    Vec3 geometricNormal() const { return glm::cross(v1 - v0, v2 - v0); }
};

// Per-ray precomputation of the shear (done once per query, not per triangle).
template <typename Real>
struct ShearedRayT {
    using V = glm::vec<3, Real>;
    V org;
    int kx, ky, kz;
    Real sx, sy, sz;

    explicit ShearedRayT(const Ray& ray) : org(ray.org) {
        const V dir(ray.dir);
        const V a = glm::abs(dir);
        kz = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
        kx = kz == 2 ? 0 : kz + 1;
        ky = kx == 2 ? 0 : kx + 1;
        if (dir[kz] < Real(0)) std::swap(kx, ky);  // keep the winding of the 2D projection
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

    // Edge functions (2D cross products). Watertightness needs a shared edge to give exactly
    // opposite values in the two triangles that share it, which evaluate it with the two
    // products' roles exchanged, so both products must be rounded alike. A compiler that
    // contracts a*b - c*d into fma(a, b, -(c*d)) rounds only one of them (GCC does by default
    // for C++ on FMA hardware, e.g. with -march=native): rays then slip between neighbours.
    // The build therefore turns contraction off (-ffp-contract=off in CMakeLists.txt; the
    // watertightness tests fail without it). Then e(a, b) == -e(b, a) exactly and coincident
    // vertices give exactly 0.
    Real e0 = cx * by - cy * bx;  // edge v1-v2: weight of v0
    Real e1 = ax * cy - ay * cx;  // edge v2-v0: weight of v1
    Real e2 = bx * ay - by * ax;  // edge v0-v1: weight of v2
    // A zero may be rounding's: the ray passes through the edge or vertex only within the
    // precision. Woop et al. recompute such cases in a wider type, where the products are
    // exact (24 + 24 bits < 53 for float; x87 long double or IEEE quad for double).
    if (e0 == Real(0) || e1 == Real(0) || e2 == Real(0)) [[unlikely]] {
        using Wide = std::conditional_t<std::is_same_v<Real, float>, double, long double>;
        e0 = Real(Wide(cx) * Wide(by) - Wide(cy) * Wide(bx));
        e1 = Real(Wide(ax) * Wide(cy) - Wide(ay) * Wide(cx));
        e2 = Real(Wide(bx) * Wide(ay) - Wide(by) * Wide(ax));
    }
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
