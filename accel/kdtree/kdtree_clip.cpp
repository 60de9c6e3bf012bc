#include "accel/kdtree/kdtree_clip.h"

#include <cmath>

namespace bvhlab::kdtree {

namespace {

// A polygon of at most 3 + 6 vertices: each of the six planes adds at most one.
struct Polygon {
    DVec3 v[9];
    int n = 0;
};

// The part of `in` where sign * (p[axis] - plane) <= 0.
void clipToPlane(const Polygon& in, Polygon& out, int axis, double plane, double sign) {
    out.n = 0;
    for (int i = 0; i < in.n; ++i) {
        const DVec3& a = in.v[i];
        const DVec3& b = in.v[(i + 1) % in.n];
        const double da = sign * (a[axis] - plane), db = sign * (b[axis] - plane);
        if (da <= 0.0) out.v[out.n++] = a;
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            DVec3 p = a + (b - a) * (da / (da - db));
            p[axis] = plane;
            out.v[out.n++] = p;
        }
    }
}

float roundDown(double x) {
    const float f = float(x);
    return double(f) > x ? std::nextafter(f, -kInfinity) : f;
}
float roundUp(double x) {
    const float f = float(x);
    return double(f) < x ? std::nextafter(f, kInfinity) : f;
}

// `b` within `box`, flat against its face where the clipped part lies only in the margin.
Bounds3 keptInside(Bounds3 b, const Bounds3& box) {
    for (int a = 0; a < 3; ++a) {
        b.lower[a] = std::min(std::max(b.lower[a], box.lower[a]), box.upper[a]);
        b.upper[a] = std::max(std::min(b.upper[a], box.upper[a]), box.lower[a]);
    }
    return b;
}

}  // namespace

Bounds3 clippedTriangleBounds(const Triangle& tri, const Bounds3& box, double margin) {
    Polygon polygon, scratch;
    polygon.v[0] = DVec3(tri.v0), polygon.v[1] = DVec3(tri.v1), polygon.v[2] = DVec3(tri.v2);
    polygon.n = 3;
    for (int a = 0; a < 3 && polygon.n > 0; ++a) {
        clipToPlane(polygon, scratch, a, double(box.lower[a]) - margin, -1.0);
        clipToPlane(scratch, polygon, a, double(box.upper[a]) + margin, 1.0);
    }
    if (polygon.n == 0) return {};
    DVec3 lo = polygon.v[0], hi = polygon.v[0];
    for (int i = 1; i < polygon.n; ++i) lo = math::min(lo, polygon.v[i]), hi = math::max(hi, polygon.v[i]);
    // Rounded outward: the double computation's own error is far below the traversal's margin.
    const Bounds3 b(Vec3(roundDown(lo.x), roundDown(lo.y), roundDown(lo.z)),
                    Vec3(roundUp(hi.x), roundUp(hi.y), roundUp(hi.z)));
    return keptInside(b, box);
}

Bounds3 clippedBounds(const PrimitiveSet& prims, uint32_t prim, const Bounds3& box, double margin) {
    if (prims.kind(prim) == PrimitiveKind::Triangle) return clippedTriangleBounds(prims.triangles[prim], box, margin);
    const Bounds3 b = intersectionOf(boundsOf(prims.quadric(prim)), box);
    return b.isEmpty() ? Bounds3() : b;
}

}  // namespace bvhlab::kdtree
