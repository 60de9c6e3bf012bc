// A ray with its valid interval and the answer to a closest-hit query.
#pragma once

#include <bvhlab/math.h>

namespace bvhlab {

inline constexpr uint32_t kInvalidPrimitive = 0xFFFFFFFFu;

// What the caller of a batch query knows of its rays. Coherent: neighbours in the batch start
// close together and point alike (a camera's rays row by row, the shadow rays of a tile towards
// one light), so they can share a walk through the tree as a packet; incoherent: any rays
// (bounces, ambient occlusion). A hint only: a structure may ignore it, and answers never
// depend on it.
enum class RayCoherence : uint32_t { Incoherent, Coherent };

// Directions need not be unit length: t is measured in multiples of dir.
struct Ray {
    Vec3 org{0.0f};
    Vec3 dir{0.0f, 0.0f, 1.0f};
    float tmin = 0.0f;
    float tmax = kInfinity;

    Vec3 at(float t) const { return org + t * dir; }
    // Rays with NaN components or an empty interval are answered as misses.
    bool isValid() const {
        return !(math::isnan(org.x) || math::isnan(org.y) || math::isnan(org.z) || math::isnan(dir.x) ||
                 math::isnan(dir.y) || math::isnan(dir.z) || math::isnan(tmin) || math::isnan(tmax)) &&
               (dir.x != 0.0f || dir.y != 0.0f || dir.z != 0.0f) && tmin <= tmax;
    }
};

// Hit convention (fixed for every accelerator, Embree's): the hit point is
// (1-u-v)*v0 + u*v1 + v*v2 of triangle `primitive`, which is its index in load order. On a
// sphere or cone (PrimitiveSet's index space) the point is org + t*dir and u = v = 0.
struct Hit {
    float t = kInfinity;
    uint32_t primitive = kInvalidPrimitive;
    float u = 0.0f;
    float v = 0.0f;

    bool found() const { return primitive != kInvalidPrimitive; }
};

// The part [t0, t1] of the ray's interval [tmin, tmax] inside the closed box [lower, upper], in
// double precision: false when there is none (also for a NaN or an infinite origin). On an axis
// the ray is parallel to, the origin must lie within the box's slab.
inline bool clipToBox(const Ray& ray, const DVec3& lower, const DVec3& upper, double& t0, double& t1) {
    t0 = ray.tmin;
    t1 = ray.tmax;
    for (int a = 0; a < 3; ++a) {
        const double org = ray.org[a], dir = ray.dir[a];
        if (dir == 0.0) {
            if (!(org >= lower[a] && org <= upper[a])) return false;
            continue;
        }
        const double inv = 1.0 / dir;
        double ta = (lower[a] - org) * inv, tb = (upper[a] - org) * inv;
        if (ta > tb) {
            const double swapped = ta;
            ta = tb;
            tb = swapped;
        }
        t0 = math::max(t0, ta);
        t1 = math::min(t1, tb);
    }
    return t0 <= t1 && math::isfinite(t0);
}

// Two closest-hit answers agree when both miss, or their t differ by at most
// 1e-4*max(1,|t|); the primitive may then differ (ties at shared edges, coincident triangles).
inline bool hitsAgree(const Hit& a, const Hit& b) {
    if (!a.found() || !b.found()) return a.found() == b.found();
    return math::abs(a.t - b.t) <= 1e-4f * math::max(1.0f, math::abs(a.t));
}

}  // namespace bvhlab
