// The one ray-triangle test all of our accelerators share: the watertight test of
// Woop, Benthin and Wald (JCGT 2013). The ray is sheared so that it runs along +z from
// the origin; the three 2D edge functions then decide inside/outside with consistent
// rounding along shared edges, so a ray cannot slip between two adjacent triangles.
#pragma once

#include "framework/core/ray.h"

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
    // products' roles exchanged. A compiler that contracts a*b - c*d into fma(a, b, -(c*d))
    // (GCC does by default for C++ on FMA hardware, e.g. with -march=native) rounds only one
    // product and breaks that symmetry: rays slip between neighbours, and a triangle whose
    // vertices coincide gets "hit". So the products are formed in a wider type where both are
    // rounded alike: double for float (exact: 24 + 24 bits < 53), and long double for double
    // (x87 on x86-64 has no fused multiply-add; IEEE quad elsewhere holds the exact product).
    // Then e(a, b) == -e(b, a) exactly and coincident vertices give exactly 0, whatever the
    // compiler's contraction setting. (Edge functions in float with a double recomputation only
    // where one is exactly 0, as Woop et al. do, were tried: cheaper, but they leaked 1 in 1e6
    // edge probes on a10. The orientation of a point against an edge must be decided exactly
    // for every edge of a vertex's fan to agree; float rounding can make all of them disagree.)
    using Wide = std::conditional_t<std::is_same_v<Real, float>, double, long double>;
    const Real e0 = Real(Wide(cx) * Wide(by) - Wide(cy) * Wide(bx));  // edge v1-v2: weight of v0
    const Real e1 = Real(Wide(ax) * Wide(cy) - Wide(ay) * Wide(cx));  // edge v2-v0: weight of v1
    const Real e2 = Real(Wide(bx) * Wide(ay) - Wide(by) * Wide(ax));  // edge v0-v1: weight of v2
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
