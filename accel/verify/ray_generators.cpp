#include "accel/verify/ray_generators.h"

#include "accel/verify/verify_rng.h"

#include <algorithm>
#include <cmath>

namespace bvhlab::verify {

namespace {

using D3 = glm::dvec3;

constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();

Bounds3 usableBounds(const Bounds3& b) {
    if (b.isEmpty()) return {Vec3(-1.0f), Vec3(1.0f)};
    return b;
}

double boundsRadius(const Bounds3& b) {
    const double r = 0.5 * glm::length(D3(b.diagonal()));
    return r > 0 ? r : 1.0;
}

// Direction scaling: rays need not be unit length; t is in multiples of dir.
Vec3 scaleDirection(VerifyRng& rng, const D3& dir) {
    const double l = glm::length(dir);
    if (!(l > 0)) return Vec3(dir);
    switch (rng.index(3)) {
        case 0:
            return Vec3(dir);  // as computed (length = distance to target)
        case 1:
            return Vec3(dir / l);  // unit
        default:
            return Vec3(dir / l * rng.logUniform(1e-2, 1e2));  // arbitrary
    }
}

const Triangle& randomValidTriangle(VerifyRng& rng, const PrimitiveSet& prims) {
    return prims.triangles[prims.valid[rng.index(prims.valid.size())]];
}

const Vec3& vertexOf(const Triangle& tri, size_t i) { return i == 0 ? tri.v0 : (i == 1 ? tri.v1 : tri.v2); }

Ray outsideRay(VerifyRng& rng, const Bounds3& bounds) {
    const D3 center(bounds.center());
    const double radius = boundsRadius(bounds);
    const Vec3 org = Vec3(center + rng.unitVector() * radius * rng.uniform(1.05, 4.0));
    const Vec3 target = rng.inBox(bounds);
    return Ray(org, scaleDirection(rng, D3(target) - D3(org)));
}

Ray insideRay(VerifyRng& rng, const Bounds3& bounds) {
    return Ray(rng.inBox(bounds), scaleDirection(rng, rng.unitVector()));
}

// A ray towards `target` from a random direction and distance (t ~ 1 at the target when the
// direction is not rescaled).
Ray aimedRay(VerifyRng& rng, const Vec3& target, double radius) {
    const double dist = radius * rng.logUniform(1e-3, 10.0);
    const Vec3 org = Vec3(D3(target) + rng.unitVector() * dist);
    return Ray(org, scaleDirection(rng, D3(target) - D3(org)));
}

Ray edgeRay(VerifyRng& rng, const PrimitiveSet& prims, double radius) {
    const Triangle& tri = randomValidTriangle(rng, prims);
    const size_t e = rng.index(3);
    const Vec3 &a = vertexOf(tri, e), &b = vertexOf(tri, (e + 1) % 3);
    const float s = rng.chance(0.2) ? 0.5f : float(rng.uniform(0.0, 1.0));
    return aimedRay(rng, a + s * (b - a), radius);
}

Ray vertexRay(VerifyRng& rng, const PrimitiveSet& prims, double radius) {
    const Triangle& tri = randomValidTriangle(rng, prims);
    return aimedRay(rng, vertexOf(tri, rng.index(3)), radius);
}

Ray axisRay(VerifyRng& rng, const PrimitiveSet& prims, const Bounds3& bounds) {
    const int axis = int(rng.index(3));
    const float scale = rng.chance(0.5) ? 1.0f : float(rng.uniform(0.25, 4.0));
    const Vec3 lo = bounds.lower, hi = bounds.upper;
    const Vec3 margin = 0.1f * bounds.diagonal() + Vec3(1e-3f);
    Vec3 org;
    const size_t mode = prims.valid.empty() ? 0 : rng.index(4);
    if (mode == 0) {
        // Anywhere in (a slightly enlarged) bounds.
        org = rng.inBox({lo - margin, hi + margin});
    } else {
        // Through a vertex's coordinates: the ray then lies exactly in planes bounding that
        // vertex's triangles (0 * inf in slab tests). Mode 2 mixes two vertices' coordinates,
        // mode 3 starts exactly at the vertex.
        org = vertexOf(randomValidTriangle(rng, prims), rng.index(3));
        if (mode == 2) {
            const Vec3 other = vertexOf(randomValidTriangle(rng, prims), rng.index(3));
            const int k = (axis + 1 + int(rng.index(2))) % 3;
            org[k] = other[k];
        }
        if (mode != 3) org[axis] = rng.chance(0.5) ? lo[axis] - margin[axis] : hi[axis] + margin[axis];
    }
    Vec3 dir(0.0f);
    // Mostly towards the scene, sometimes away from it.
    const bool towardsLower = org[axis] > 0.5f * (lo[axis] + hi[axis]);
    const bool negative = rng.chance(0.85) ? towardsLower : !towardsLower;
    dir[axis] = negative ? -scale : scale;
    return Ray(org, dir);
}

Ray grazingRay(VerifyRng& rng, const PrimitiveSet& prims, double radius) {
    const Triangle& tri = randomValidTriangle(rng, prims);
    const D3 v0(tri.v0), v1(tri.v1), v2(tri.v2);
    const D3 n = glm::normalize(glm::cross(v1 - v0, v2 - v0));
    D3 w = glm::cross(n, rng.unitVector());
    while (glm::length(w) < 1e-3) w = glm::cross(n, rng.unitVector());
    w = glm::normalize(w);
    const double angle = rng.chance(0.1) ? 0.0 : (rng.chance(0.5) ? 1 : -1) * rng.logUniform(1e-6, 1e-1);
    const D3 dir = w * std::cos(angle) + n * std::sin(angle);
    double a = rng.uniform(), b = rng.uniform();
    if (a + b > 1) a = 1 - a, b = 1 - b;
    if (rng.chance(0.2)) b = 0;  // on an edge
    const D3 target = v0 + a * (v1 - v0) + b * (v2 - v0);
    const double size = std::max({glm::length(v1 - v0), glm::length(v2 - v0), 1e-30});
    const double dist = std::min(radius, size) * rng.logUniform(0.1, 10.0);
    return Ray(Vec3(target - dir * dist), scaleDirection(rng, dir));
}

Ray intervalRay(VerifyRng& rng, const PrimitiveSet& prims, const Bounds3& bounds) {
    const size_t mode = prims.valid.empty() ? 1 + rng.index(4) : rng.index(5);
    switch (mode) {
        case 0: {
            // Very short ray ending just before or just after a surface point (or starting there).
            const Triangle& tri = randomValidTriangle(rng, prims);
            const D3 v0(tri.v0), v1(tri.v1), v2(tri.v2);
            const D3 n = glm::normalize(glm::cross(v1 - v0, v2 - v0));
            D3 dir = rng.unitVector();
            while (std::abs(glm::dot(dir, n)) < 0.2) dir = rng.unitVector();
            const double a = rng.uniform(0.1, 0.45), b = rng.uniform(0.1, 0.45);
            const D3 target = v0 + a * (v1 - v0) + b * (v2 - v0);
            const double size = std::max(glm::length(v1 - v0), glm::length(v2 - v0));
            const double delta = size * rng.logUniform(1e-5, 1.0);
            Ray r = Ray(Vec3(target - dir * delta), Vec3(dir));
            const double f = rng.logUniform(1e-6, 1e-2) * (rng.chance(0.5) ? 1 : -1);
            if (rng.chance(0.7)) {
                r.tmax = float(delta * (1 + f));  // ends just past / just before the surface
            } else {
                r.tmin = float(delta * (1 + f));  // starts just past / just before it
            }
            return r;
        }
        case 1: {
            // tmin > 0 on an outside ray (t = 1 at a point inside the bounds).
            Ray r = outsideRay(rng, bounds);
            const D3 toCenter = D3(bounds.center()) - D3(r.org);
            const double tCenter = glm::length(toCenter) / glm::length(D3(r.dir));
            r.tmin = float(tCenter * rng.uniform(0.0, 1.5));
            r.tmax = rng.chance(0.3) ? kInfinity : float(r.tmin + tCenter * rng.uniform(0.0, 1.0));
            return r;
        }
        case 2: {
            // tmin == tmax: a single point of the ray.
            Ray r = outsideRay(rng, bounds);
            r.tmin = r.tmax =
                float(rng.uniform(0.0, 2.0) * glm::length(D3(bounds.center()) - D3(r.org)) / glm::length(D3(r.dir)));
            return r;
        }
        case 3: {
            // Negative tmin from inside: hits behind the origin count.
            Ray r = insideRay(rng, bounds);
            const double scale = boundsRadius(bounds) / glm::length(D3(r.dir));
            r.tmin = -float(scale * rng.uniform(0.0, 2.0));
            r.tmax = rng.chance(0.5) ? kInfinity : float(scale * rng.uniform(-0.5, 2.0));
            if (r.tmax < r.tmin) std::swap(r.tmin, r.tmax);
            return r;
        }
        default: {
            // tmin > tmax: an empty interval, must miss.
            Ray r = outsideRay(rng, bounds);
            r.tmin = float(rng.uniform(0.5, 2.0));
            r.tmax = std::nextafter(r.tmin, -kInfinity) * float(rng.uniform(0.0, 1.0));
            return r;
        }
    }
}

Ray invalidRay(VerifyRng& rng, const Bounds3& bounds) {
    Ray r = outsideRay(rng, bounds);
    float* fields[8] = {&r.org.x, &r.org.y, &r.org.z, &r.dir.x, &r.dir.y, &r.dir.z, &r.tmin, &r.tmax};
    switch (rng.index(4)) {
        case 0:
            *fields[rng.index(8)] = kNaNf;
            break;  // one NaN
        case 1:
            *fields[rng.index(8)] = kNaNf;
            *fields[rng.index(8)] = kNaNf;
            break;
        case 2:
            for (float* f : fields) *f = kNaNf;
            break;
        default:
            r.dir = Vec3(0.0f);
            break;  // zero direction
    }
    return r;
}

}  // namespace

const char* rayKindName(RayKind kind) {
    switch (kind) {
        case RayKind::Outside:
            return "outside";
        case RayKind::Inside:
            return "inside";
        case RayKind::EdgeAimed:
            return "edge";
        case RayKind::VertexAimed:
            return "vertex";
        case RayKind::AxisParallel:
            return "axis";
        case RayKind::Grazing:
            return "grazing";
        case RayKind::Interval:
            return "interval";
        case RayKind::Invalid:
            return "invalid";
    }
    return "?";
}
size_t raysPerKind(const Scene& scene, RayKind kind) {
    if (kind == RayKind::Invalid) return 200;
    const size_t n = scene.validPrimitives.size();
    if (n <= 3) return 4000;
    if (n <= 5000) return 1500;
    // Past ~12k triangles (a user's scene) fewer rays, so that the oracle's work per kind stays
    // near 1e7 triangle tests however large the scene.
    return std::clamp<size_t>(10'000'000 / n, 100, 800);
}

std::vector<Ray> generateRays(RayKind kind, const PrimitiveSet& prims, const Bounds3& sceneBounds, size_t count,
                              uint32_t seed) {
    VerifyRng rng(seed * 2654435761u + uint32_t(kind) * 40503u + 17u);
    const Bounds3 bounds = usableBounds(sceneBounds);
    const double radius = boundsRadius(bounds);
    const bool haveTriangles = !prims.valid.empty();
    std::vector<Ray> rays;
    rays.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        switch (kind) {
            case RayKind::Outside:
                rays.push_back(outsideRay(rng, bounds));
                break;
            case RayKind::Inside:
                rays.push_back(insideRay(rng, bounds));
                break;
            case RayKind::EdgeAimed:
                rays.push_back(haveTriangles ? edgeRay(rng, prims, radius) : outsideRay(rng, bounds));
                break;
            case RayKind::VertexAimed:
                rays.push_back(haveTriangles ? vertexRay(rng, prims, radius) : outsideRay(rng, bounds));
                break;
            case RayKind::AxisParallel:
                rays.push_back(axisRay(rng, prims, bounds));
                break;
            case RayKind::Grazing:
                rays.push_back(haveTriangles ? grazingRay(rng, prims, radius) : outsideRay(rng, bounds));
                break;
            case RayKind::Interval:
                rays.push_back(intervalRay(rng, prims, bounds));
                break;
            case RayKind::Invalid:
                rays.push_back(invalidRay(rng, bounds));
                break;
        }
    }
    return rays;
}

std::vector<Ray> raysTowardTriangles(const Scene& scene, size_t count, uint64_t seed) {
    std::vector<Ray> rays;
    const View<const uint32_t> valid = scene.primitives().validTriangles();  // not the quadrics after them
    if (valid.empty()) return rays;
    VerifyRng rng(seed);
    const DVec3 centre(scene.bounds.center());
    const double radius = 0.5 * glm::length(DVec3(scene.bounds.diagonal()));
    rays.reserve(count);
    while (rays.size() < count) {
        const Triangle& tri = scene.triangles[valid[rng.index(valid.size())]];
        double u, v;
        do {
            u = rng.uniform();
            v = rng.uniform();
        } while (u < 0.1 || v < 0.1 || 1.0 - u - v < 0.1);
        const DVec3 q = (1.0 - u - v) * DVec3(tri.v0) + u * DVec3(tri.v1) + v * DVec3(tri.v2);
        const DVec3 n = glm::normalize(glm::cross(DVec3(tri.v1) - DVec3(tri.v0), DVec3(tri.v2) - DVec3(tri.v0)));
        const DVec3 d = rng.unitVector();
        if (std::abs(glm::dot(d, n)) < 0.2) continue;  // not within ~11.5 degrees of grazing
        const Vec3 org(q - d * (glm::length(q - centre) + radius * rng.uniform(1.1, 3.0)));
        const DVec3 dir = glm::normalize(q - DVec3(org));
        rays.push_back(Ray{org, Vec3(dir), 0.0f, kInfinity});
    }
    return rays;
}

}  // namespace bvhlab::verify
