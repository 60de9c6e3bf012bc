#include "apps/check/oracle.h"

#include "framework/core/triangle.h"
#include "framework/robustness/stress_scenes.h"
#include "framework/scene/procedural.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>

namespace bvhlab::check {

namespace {

using D3 = glm::dvec3;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();

// ---------------------------------------------------------------------------------------------
// Error model of the float watertight test (framework/core/triangle.h), used by the judge.
//
// The test subtracts the origin from each vertex and shears: every sheared coordinate carries
// an absolute error of a few ulps of M = max |v_i - org| (infinity norm). The inside/outside
// decision is therefore uncertain for rays passing within ~c*eps*M of an edge (laterally), and
// t is uncertain by that lateral error times tan(incidence) plus a few ulps of M, over |dir|.
// kErrorUlps is deliberately generous (float eps = 2^-24, so 64 ulps ~ 4e-6 relative): an
// answer is only called Wrong when it is off by far more than any rounding can explain.
constexpr double kFloatEps = 1.0 / 16777216.0;
constexpr double kErrorUlps = 64.0;

struct TriangleGeometry {
    D3 v0, v1, v2;
    D3 normal;         // unnormalised, cross(v1 - v0, v2 - v0)
    double normalLen;  // twice the area
    double cosine;     // |cos| of the angle between the ray and the normal
    double tolLateral; // absolute distance
    double tolT;       // in units of t
};

TriangleGeometry geometryOf(const Triangle& tri, const Ray& ray) {
    TriangleGeometry g;
    g.v0 = D3(tri.v0);
    g.v1 = D3(tri.v1);
    g.v2 = D3(tri.v2);
    const D3 org(ray.org), dir(ray.dir);
    g.normal = glm::cross(g.v1 - g.v0, g.v2 - g.v0);
    g.normalLen = glm::length(g.normal);
    const double dirLen = glm::length(dir);
    g.cosine = g.normalLen > 0 ? std::abs(glm::dot(g.normal, dir)) / (g.normalLen * dirLen) : 0.0;
    double m = 0.0;
    for (const D3& v : {g.v0, g.v1, g.v2})
        for (int k = 0; k < 3; ++k) m = std::max(m, std::abs(v[k] - org[k]));
    g.tolLateral = kErrorUlps * kFloatEps * m;
    const double c = std::min(1.0, g.cosine);
    const double tangent = c > 0 ? std::sqrt(std::max(0.0, 1.0 - c * c)) / c : kInf;
    g.tolT = (g.tolLateral * tangent + kErrorUlps * kFloatEps * m) / dirLen;
    return g;
}

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5).
D3 closestPointOnTriangle(const D3& p, const D3& a, const D3& b, const D3& c) {
    const D3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const D3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
    const D3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

// In-plane distance from the point with barycentric weights (1-u-v, u, v) to the triangle's
// boundary (negative weights give 0).
double boundaryDistance(const TriangleGeometry& g, double u, double v) {
    const double w[3] = {1.0 - u - v, u, v};
    const double opposite[3] = {glm::length(g.v2 - g.v1), glm::length(g.v0 - g.v2), glm::length(g.v1 - g.v0)};
    double d = kInf;
    for (int i = 0; i < 3; ++i) d = std::min(d, std::max(0.0, w[i]) * g.normalLen / opposite[i]);
    return d;
}

// Barycentric weights (of v1, v2) of p projected onto the triangle's plane.
std::pair<double, double> barycentricOf(const TriangleGeometry& g, const D3& p) {
    const D3 e1 = g.v1 - g.v0, e2 = g.v2 - g.v0, ep = p - g.v0;
    const double d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
    const double d20 = glm::dot(ep, e1), d21 = glm::dot(ep, e2);
    const double denom = d00 * d11 - d01 * d01;
    return {(d11 * d20 - d01 * d21) / denom, (d00 * d21 - d01 * d20) / denom};
}

double minAltitude(const TriangleGeometry& g) {
    const double longest =
        std::max({glm::length(g.v1 - g.v0), glm::length(g.v2 - g.v1), glm::length(g.v0 - g.v2)});
    return g.normalLen / longest;
}

// ---------------------------------------------------------------------------------------------
// Random helpers (the random numbers are StressRng's, framework/robustness/stress_rng.h).

Bounds3 usableBounds(const Bounds3& b) {
    if (b.isEmpty()) return {Vec3(-1.0f), Vec3(1.0f)};
    return b;
}

double boundsRadius(const Bounds3& b) {
    const double r = 0.5 * glm::length(D3(b.diagonal()));
    return r > 0 ? r : 1.0;
}

// Direction scaling: rays need not be unit length; t is in multiples of dir.
Vec3 scaleDirection(StressRng& rng, const D3& dir) {
    const double l = glm::length(dir);
    if (!(l > 0)) return Vec3(dir);
    switch (rng.index(3)) {
    case 0: return Vec3(dir);                        // as computed (length = distance to target)
    case 1: return Vec3(dir / l);                    // unit
    default: return Vec3(dir / l * rng.logUniform(1e-2, 1e2));  // arbitrary
    }
}

const Triangle& randomValidTriangle(StressRng& rng, const PrimitiveSet& prims) {
    return prims.triangles[prims.valid[rng.index(prims.valid.size())]];
}

const Vec3& vertexOf(const Triangle& tri, size_t i) { return i == 0 ? tri.v0 : (i == 1 ? tri.v1 : tri.v2); }

Ray outsideRay(StressRng& rng, const Bounds3& bounds) {
    const D3 center(bounds.center());
    const double radius = boundsRadius(bounds);
    const Vec3 org = Vec3(center + rng.unitVector() * radius * rng.uniform(1.05, 4.0));
    const Vec3 target = rng.inBox(bounds);
    return Ray(org, scaleDirection(rng, D3(target) - D3(org)));
}

Ray insideRay(StressRng& rng, const Bounds3& bounds) {
    return Ray(rng.inBox(bounds), scaleDirection(rng, rng.unitVector()));
}

// A ray towards `target` from a random direction and distance (t ~ 1 at the target when the
// direction is not rescaled).
Ray aimedRay(StressRng& rng, const Vec3& target, double radius) {
    const double dist = radius * rng.logUniform(1e-3, 10.0);
    const Vec3 org = Vec3(D3(target) + rng.unitVector() * dist);
    return Ray(org, scaleDirection(rng, D3(target) - D3(org)));
}

Ray edgeRay(StressRng& rng, const PrimitiveSet& prims, double radius) {
    const Triangle& tri = randomValidTriangle(rng, prims);
    const size_t e = rng.index(3);
    const Vec3 &a = vertexOf(tri, e), &b = vertexOf(tri, (e + 1) % 3);
    const float s = rng.chance(0.2) ? 0.5f : float(rng.uniform(0.0, 1.0));
    return aimedRay(rng, a + s * (b - a), radius);
}

Ray vertexRay(StressRng& rng, const PrimitiveSet& prims, double radius) {
    const Triangle& tri = randomValidTriangle(rng, prims);
    return aimedRay(rng, vertexOf(tri, rng.index(3)), radius);
}

Ray axisRay(StressRng& rng, const PrimitiveSet& prims, const Bounds3& bounds) {
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

Ray grazingRay(StressRng& rng, const PrimitiveSet& prims, double radius) {
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

Ray intervalRay(StressRng& rng, const PrimitiveSet& prims, const Bounds3& bounds) {
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
        r.tmin = r.tmax = float(rng.uniform(0.0, 2.0) * glm::length(D3(bounds.center()) - D3(r.org)) /
                                glm::length(D3(r.dir)));
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

Ray invalidRay(StressRng& rng, const Bounds3& bounds) {
    Ray r = outsideRay(rng, bounds);
    float* fields[8] = {&r.org.x, &r.org.y, &r.org.z, &r.dir.x, &r.dir.y, &r.dir.z, &r.tmin, &r.tmax};
    switch (rng.index(4)) {
    case 0: *fields[rng.index(8)] = kNaNf; break;  // one NaN
    case 1:
        *fields[rng.index(8)] = kNaNf;
        *fields[rng.index(8)] = kNaNf;
        break;
    case 2:
        for (float* f : fields) *f = kNaNf;
        break;
    default: r.dir = Vec3(0.0f); break;  // zero direction
    }
    return r;
}

// A soup's triangle: of a log-uniform size in [minSize, maxSize], near a uniform point of `box`.
void addSoupTriangle(Scene& scene, StressRng& rng, const Bounds3& box, double minSize, double maxSize) {
    const D3 c(rng.inBox(box));
    const double size = rng.logUniform(minSize, maxSize);
    addLooseTriangle(scene, Vec3(c + rng.unitVector() * size), Vec3(c + rng.unitVector() * size),
                     Vec3(c + rng.unitVector() * size));
}

}  // namespace

// ---------------------------------------------------------------------------------------------

const char* verdictName(Verdict v) {
    switch (v) {
    case Verdict::Right: return "right";
    case Verdict::Ambiguous: return "ambiguous";
    case Verdict::Wrong: return "WRONG";
    }
    return "?";
}

const char* rayKindName(RayKind kind) {
    switch (kind) {
    case RayKind::Outside: return "outside";
    case RayKind::Inside: return "inside";
    case RayKind::EdgeAimed: return "edge";
    case RayKind::VertexAimed: return "vertex";
    case RayKind::AxisParallel: return "axis";
    case RayKind::Grazing: return "grazing";
    case RayKind::Interval: return "interval";
    case RayKind::Invalid: return "invalid";
    }
    return "?";
}

Oracle::Oracle(const PrimitiveSet& prims) : prims_(prims), valid_(prims.triangles.size(), 0) {
    if (prims.hasQuadrics())
        throw std::invalid_argument("Oracle: triangles only (scenes with spheres and cones: test_mixed_primitives.cpp)");
    for (uint32_t p : prims.valid) valid_.at(p) = 1;
}

OracleHit Oracle::nearest(const Ray& ray) const {
    OracleHit best;
    if (!ray.isValid()) return best;
    const ShearedRayT<double> sheared(ray);
    for (uint32_t prim : prims_.valid) {
        TriangleHitT<double> h;
        if (!intersectTriangle<double>(sheared, prims_.triangles[prim], double(ray.tmin), double(ray.tmax), h))
            continue;
        if (h.t < best.t || (h.t == best.t && prim < best.primitive)) best = {h.t, prim, h.u, h.v};
    }
    return best;
}

bool Oracle::occluded(const Ray& ray) const {
    if (!ray.isValid()) return false;
    const ShearedRayT<double> sheared(ray);
    TriangleHitT<double> h;
    for (uint32_t prim : prims_.valid)
        if (intersectTriangle<double>(sheared, prims_.triangles[prim], double(ray.tmin), double(ray.tmax), h))
            return true;
    return false;
}

std::vector<OracleHit> Oracle::allHits(const Ray& ray) const {
    std::vector<OracleHit> hits;
    if (!ray.isValid()) return hits;
    const ShearedRayT<double> sheared(ray);
    for (uint32_t prim : prims_.valid) {
        TriangleHitT<double> h;
        if (intersectTriangle<double>(sheared, prims_.triangles[prim], double(ray.tmin), double(ray.tmax), h))
            hits.push_back({h.t, prim, h.u, h.v});
    }
    std::sort(hits.begin(), hits.end(), [](const OracleHit& a, const OracleHit& b) {
        return a.t < b.t || (a.t == b.t && a.primitive < b.primitive);
    });
    return hits;
}

Judgement Oracle::judge(const Ray& ray, const Hit& answer) const { return judge(ray, answer, nearest(ray)); }

Judgement Oracle::judge(const Ray& ray, const Hit& answer, const OracleHit& nearestHit) const {
    if (!ray.isValid()) {
        if (answer.found()) return {Verdict::Wrong, "a hit on an invalid ray (NaN or empty interval)"};
        return {};
    }
    const D3 org(ray.org), dir(ray.dir);
    const double dirLen = glm::length(dir);
    TriangleGeometry claimed{};
    if (answer.found()) {
        // The claim itself: a valid primitive, a t in the interval, a point on that triangle,
        // and u, v giving that point.
        const uint32_t p = answer.primitive;
        if (!isValidPrimitive(p))
            return {Verdict::Wrong, fmt::format("primitive {} is not a valid (non-degenerate, built) primitive", p)};
        if (!(answer.t >= ray.tmin && answer.t <= ray.tmax))
            return {Verdict::Wrong, fmt::format("t = {:.9g} is outside [{:.9g}, {:.9g}]", answer.t, ray.tmin, ray.tmax)};
        claimed = geometryOf(prims_.triangles[p], ray);
        const D3 q = org + double(answer.t) * dir;
        const double dist = glm::length(q - closestPointOnTriangle(q, claimed.v0, claimed.v1, claimed.v2));
        const double c = std::max(claimed.cosine, 1e-300);
        const double tol = claimed.tolLateral * (1.0 + 1.0 / c) + claimed.tolT * dirLen;
        if (dist > tol)
            return {Verdict::Wrong, fmt::format("the point at t = {:.9g} is {:.3g} from triangle {} (bound {:.3g})",
                                                answer.t, dist, p, tol)};
        if (!(answer.u >= -1e-6f && answer.v >= -1e-6f && answer.u + answer.v <= 1.0f + 1e-5f))
            return {Verdict::Wrong, fmt::format("u = {:.9g}, v = {:.9g} are not barycentric weights", answer.u, answer.v)};
        const auto [bu, bv] = barycentricOf(claimed, q);
        const double tolBary = 2.0 * tol / minAltitude(claimed) + 1e-5;
        if (std::abs(bu - answer.u) > tolBary || std::abs(bv - answer.v) > tolBary)
            return {Verdict::Wrong,
                    fmt::format("u, v = ({:.9g}, {:.9g}) but the hit point has weights ({:.9g}, {:.9g}) of v1, v2 "
                                "(bound {:.3g})",
                                answer.u, answer.v, bu, bv, tolBary)};
    }
    if (agree(answer, nearestHit.toHit())) return {};

    // Differs from the oracle. Wrong only if the oracle has an unambiguous hit (away from every
    // edge and interval end by more than the error bound) clearly in front of the answer.
    for (const OracleHit& h : allHits(ray)) {
        const TriangleGeometry g = geometryOf(prims_.triangles[h.primitive], ray);
        const bool awayFromEdges = boundaryDistance(g, h.u, h.v) * g.cosine > 2.0 * g.tolLateral;
        const bool awayFromEnds = h.t - double(ray.tmin) > g.tolT && double(ray.tmax) - h.t > g.tolT;
        if (!awayFromEdges || !awayFromEnds) continue;
        if (!answer.found())
            return {Verdict::Wrong, fmt::format("missed an unambiguous hit: {}", describe(h))};
        const double margin = g.tolT + claimed.tolT + 1e-4 * std::max(1.0, std::abs(double(answer.t)));
        if (h.t < double(answer.t) - margin)
            return {Verdict::Wrong, fmt::format("missed an unambiguous closer hit: {}", describe(h))};
        break;  // hits are sorted: later ones are farther
    }
    return {Verdict::Ambiguous, fmt::format("differs from the oracle ({}) within error bounds", describe(nearestHit))};
}

// ---------------------------------------------------------------------------------------------

size_t raysPerKind(const Scene& scene, RayKind kind) {
    if (kind == RayKind::Invalid) return 200;
    const size_t n = scene.validPrimitives.size();
    if (n <= 3) return 4000;
    return n > 5000 ? 800 : 1500;
}

std::vector<Ray> generateRays(RayKind kind, const PrimitiveSet& prims, const Bounds3& sceneBounds, size_t count,
                              uint32_t seed) {
    StressRng rng(seed * 2654435761u + uint32_t(kind) * 40503u + 17u);
    const Bounds3 bounds = usableBounds(sceneBounds);
    const double radius = boundsRadius(bounds);
    const bool haveTriangles = !prims.valid.empty();
    std::vector<Ray> rays;
    rays.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        switch (kind) {
        case RayKind::Outside: rays.push_back(outsideRay(rng, bounds)); break;
        case RayKind::Inside: rays.push_back(insideRay(rng, bounds)); break;
        case RayKind::EdgeAimed:
            rays.push_back(haveTriangles ? edgeRay(rng, prims, radius) : outsideRay(rng, bounds));
            break;
        case RayKind::VertexAimed:
            rays.push_back(haveTriangles ? vertexRay(rng, prims, radius) : outsideRay(rng, bounds));
            break;
        case RayKind::AxisParallel: rays.push_back(axisRay(rng, prims, bounds)); break;
        case RayKind::Grazing:
            rays.push_back(haveTriangles ? grazingRay(rng, prims, radius) : outsideRay(rng, bounds));
            break;
        case RayKind::Interval: rays.push_back(intervalRay(rng, prims, bounds)); break;
        case RayKind::Invalid: rays.push_back(invalidRay(rng, bounds)); break;
        }
    }
    return rays;
}

std::vector<WatertightProbe> watertightProbes(const Scene& mesh, const std::function<Vec3(const Vec3&)>& interiorPointNear,
                                              bool convex, size_t perEdge, size_t perVertex, uint32_t seed) {
    StressRng rng(seed);
    using Key3 = std::array<float, 3>;
    using Key6 = std::array<float, 6>;
    auto key3 = [](const Vec3& v) { return Key3{v.x, v.y, v.z}; };
    // Outward unit normals, and faces by edge and by vertex (matched by position, so meshes that
    // repeat vertices per face, like addBox, are handled too).
    std::vector<D3> normals(mesh.triangles.size());
    std::map<Key6, std::vector<uint32_t>> facesOfEdge;
    std::map<Key3, std::vector<uint32_t>> facesOfVertex;
    for (uint32_t prim : mesh.validPrimitives) {
        const Triangle& tri = mesh.triangles[prim];
        D3 n = glm::normalize(D3(tri.geometricNormal()));
        const D3 centroid(tri.centroid());
        if (glm::dot(n, centroid - D3(interiorPointNear(tri.centroid()))) < 0) n = -n;
        normals[prim] = n;
        for (int e = 0; e < 3; ++e) {
            Key3 a = key3(vertexOf(tri, e)), b = key3(vertexOf(tri, (e + 1) % 3));
            if (b < a) std::swap(a, b);
            facesOfEdge[{a[0], a[1], a[2], b[0], b[1], b[2]}].push_back(prim);
            facesOfVertex[key3(vertexOf(tri, e))].push_back(prim);
        }
    }
    const double meshSize = boundsRadius(mesh.bounds);

    // A direction within the cone of outward normals (at least 0.2 along each), and a probe from
    // outside along it through p.
    auto probe = [&](const Vec3& p, const std::vector<uint32_t>& faces, double localSize, bool atVertex,
                     std::vector<WatertightProbe>& out) {
        D3 base(0.0);
        for (uint32_t f : faces) base += normals[f];
        if (glm::length(base) < 1e-9) return;
        base = glm::normalize(base);
        auto inCone = [&](const D3& d) {
            for (uint32_t f : faces)
                if (glm::dot(d, normals[f]) < 0.2) return false;
            return true;
        };
        D3 d = base;
        for (int tries = 0; tries < 50; ++tries) {
            const D3 candidate = glm::normalize(base + 0.8 * rng.unitVector());
            if (inCone(candidate)) {
                d = candidate;
                break;
            }
        }
        if (!inCone(d)) return;
        const double dist = convex ? meshSize * rng.logUniform(1e-2, 1e3) : localSize * rng.logUniform(0.05, 1.0);
        const Vec3 org = Vec3(D3(p) + d * dist);
        Ray ray = Ray(org, p - org);
        // Rounding of org and dir moves the ray off p by a few ulps of |org| + |p|; t at the
        // surface then moves by that times tan(incidence) <= 5 over |dir|.
        double scale = 0;
        for (int k = 0; k < 3; ++k) scale = std::max({scale, std::abs(double(org[k])), std::abs(double(p[k]))});
        const double slack = 1e-7 + 64.0 * kFloatEps * scale * 5.0 / glm::length(D3(ray.dir));
        out.push_back({ray, 1.0 + slack, atVertex});
    };

    std::vector<WatertightProbe> probes;
    for (const auto& [key, faces] : facesOfEdge) {
        if (faces.size() != 2) continue;  // boundary or non-manifold edge: nothing to probe
        const Vec3 a(key[0], key[1], key[2]), b(key[3], key[4], key[5]);
        for (size_t i = 0; i < perEdge; ++i) {
            const float s = float(rng.uniform(0.02, 0.98));
            probe(a + s * (b - a), faces, glm::length(D3(b - a)), false, probes);
        }
    }
    for (const auto& [key, faces] : facesOfVertex) {
        const Vec3 v(key[0], key[1], key[2]);
        double localSize = kInf;
        for (uint32_t f : faces)
            for (int e = 0; e < 3; ++e) {
                const double l = glm::length(D3(vertexOf(mesh.triangles[f], e)) - D3(v));
                if (l > 0) localSize = std::min(localSize, l);
            }
        for (size_t i = 0; i < perVertex; ++i) probe(v, faces, localSize, true, probes);
    }
    return probes;
}

// ---------------------------------------------------------------------------------------------

Scene sceneFromTriangles(const std::vector<Triangle>& triangles, const std::string& name) {
    Scene scene;
    scene.name = name;
    for (const Triangle& t : triangles) addLooseTriangle(scene, t.v0, t.v1, t.v2);
    scene.finalize();
    return scene;
}

Scene makeSoupScene(size_t count, uint32_t seed, float minSize, float maxSize, float extent) {
    StressRng rng(seed);
    Scene scene;
    scene.name = "soup";
    const Bounds3 box(Vec3(-0.5f * extent), Vec3(0.5f * extent));
    for (size_t i = 0; i < count; ++i) addSoupTriangle(scene, rng, box, minSize, maxSize);
    scene.finalize();
    return scene;
}

Scene makeClosedMeshesScene() {
    Scene scene;
    scene.name = "closed";
    addIcosphere(scene, Vec3(-3.0f, 0.0f, 0.0f), 1.2f, 3, 0);
    addBox(scene, Vec3(0.5f, -1.0f, -1.0f), Vec3(2.5f, 1.0f, 1.25f), 0);
    addTorus(scene, Vec3(5.5f, 0.0f, 0.3f), 1.5f, 0.5f, 32, 16, 0);
    scene.finalize();
    return scene;
}

Scene makeTerrainScene(int cells, uint32_t seed) {
    StressRng rng(seed);
    Scene scene;
    scene.name = "terrain";
    const int n = cells + 1;
    const double phase = rng.uniform(0, 6.28);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const float x = float(i) / float(cells) * 20.0f - 10.0f, z = float(j) / float(cells) * 20.0f - 10.0f;
            // A flat plateau at exactly 0 in one quarter (zero-thickness boxes), hills elsewhere.
            float h = 0.0f;
            if (i > n / 2 || j > n / 2)
                h = float(1.5 * std::sin(0.7 * x + phase) * std::cos(0.5 * z) + 0.05 * rng.uniform(-1, 1));
            scene.positions.emplace_back(x, h, z);
        }
    for (int i = 0; i < cells; ++i)
        for (int j = 0; j < cells; ++j) {
            const uint32_t a = uint32_t(i * n + j), b = a + 1, c = a + uint32_t(n), d = c + 1;
            scene.indices.emplace_back(a, b, d);
            scene.indices.emplace_back(a, d, c);
        }
    scene.finalize();
    return scene;
}

Scene makeCostScene() {
    StressRng rng(21);
    Scene scene;
    scene.name = "cost";
    addQuad(scene, Vec3(-20, 0, -20), Vec3(0, 0, 40), Vec3(40, 0, 0), 0);
    for (int i = 0; i < 6; ++i) {
        const Vec3 corner(-14.0f + 5.0f * float(i), 0.0f, -12.0f + 2.0f * float(i % 3));
        addBox(scene, corner, corner + Vec3(2.0f, 1.0f + float(i), 1.5f), 0);
    }
    addIcosphere(scene, Vec3(-4.0f, 2.0f, 0.0f), 2.0f, 5, 0);
    addTorus(scene, Vec3(4.0f, 1.0f, 2.0f), 2.0f, 0.6f, 96, 48, 0);
    const Bounds3 air(Vec3(-15.0f, 3.0f, -15.0f), Vec3(15.0f, 10.0f, 15.0f));
    for (int i = 0; i < 2000; ++i) addSoupTriangle(scene, rng, air, 0.05, 0.5);
    scene.finalize();
    return scene;
}

Scene makeCoincidentScene(uint32_t seed) {
    StressRng rng(seed);
    Scene scene;
    scene.name = "coincident";
    const Bounds3 box(Vec3(-5.0f), Vec3(5.0f));
    for (int i = 0; i < 200; ++i) {
        const D3 c(rng.inBox(box));
        const double size = rng.logUniform(0.05, 2.0);
        const Vec3 a = Vec3(c + rng.unitVector() * size), b = Vec3(c + rng.unitVector() * size),
                   d = Vec3(c + rng.unitVector() * size);
        addLooseTriangle(scene, a, b, d);
        addLooseTriangle(scene, a, b, d);  // identical
        addLooseTriangle(scene, a, d, b);  // reversed winding
        addLooseTriangle(scene, b, d, a);  // rotated vertex order
        // Coplanar, overlapping: the same triangle slid within its plane.
        const Vec3 shift = 0.3f * (b - a);
        addLooseTriangle(scene, a + shift, b + shift, d + shift);
    }
    scene.finalize();
    return scene;
}

Scene makeCentroidsOnLineScene(size_t count, uint32_t seed) {
    // Few distinct positions along x, so that many centroids coincide exactly.
    return makeTrianglesAroundScene(
        "centroids_line", count, seed, [](StressRng& rng) { return D3(double(rng.index(25)) * 0.8 - 10.0, 0.0, 0.0); },
        [](StressRng& rng) { return rng.uniform(0.1, 1.0); });
}

Scene makeCentroidsOnPlaneScene(size_t count, uint32_t seed) {
    // Braced, so that x is drawn before y on every compiler.
    return makeTrianglesAroundScene(
        "centroids_plane", count, seed, [](StressRng& rng) { return D3{rng.uniform(-10, 10), rng.uniform(-10, 10), 0.0}; },
        [](StressRng& rng) { return rng.uniform(0.1, 1.0); });
}

Scene makeCentroidsAtPointScene(size_t count, uint32_t seed) {
    return makeTrianglesAroundScene(
        "centroids_point", count, seed, [](StressRng&) { return D3(1.0, 2.0, 3.0); },
        [](StressRng& rng) { return rng.logUniform(1e-2, 10.0); });
}

Scene makeTinyScene(int triangles, uint32_t seed) {
    StressRng rng(seed);
    Scene scene;
    scene.name = fmt::format("tiny{}", triangles);
    const Bounds3 box(Vec3(-1.0f), Vec3(1.0f));
    for (int i = 0; i < triangles; ++i) addLooseTriangle(scene, rng.inBox(box), rng.inBox(box), rng.inBox(box));
    scene.finalize();
    return scene;
}

Scene makeDegenerateMixScene(size_t count, uint32_t seed) {
    StressRng rng(seed);
    Scene scene;
    scene.name = "degenerate_mix";
    const Bounds3 box(Vec3(-10.0f), Vec3(10.0f));
    // Small integers / 4: sums of these are exact, so the segments below are exactly collinear.
    auto grid = [&] { return Vec3(float(int(rng.index(64)) - 32), float(int(rng.index(64)) - 32), float(int(rng.index(64)) - 32)) * 0.25f; };
    const float inf = std::numeric_limits<float>::infinity();
    for (size_t i = 0; i < count; ++i) {
        if (!rng.chance(0.25)) {
            addSoupTriangle(scene, rng, box, 1e-2, 5.0);
            continue;
        }
        const Vec3 p = grid(), q = grid();
        const Vec3 d = Vec3(float(int(rng.index(5)) - 2), float(int(rng.index(5)) - 2), float(int(rng.index(5)) - 2)) * 0.25f;
        switch (rng.index(6)) {
        case 0: addLooseTriangle(scene, p, p, p); break;                  // a point
        case 1: addLooseTriangle(scene, p, p + d, p + 2.0f * d); break;  // an exact segment
        case 2: addLooseTriangle(scene, p, q, p); break;                  // a repeated vertex
        case 3: addLooseTriangle(scene, p, q, Vec3(q.x, kNaNf, q.z)); break;
        case 4: addLooseTriangle(scene, Vec3(inf, p.y, p.z), p, q); break;
        default: addLooseTriangle(scene, p, Vec3(kNaNf), q); break;
        }
    }
    scene.finalize();
    return scene;
}

const std::vector<NamedSceneFactory>& generatedScenes() {
    static const std::vector<NamedSceneFactory> scenes = {
        {"soup_mixed", [] { return makeSoupScene(3000, 1); }},  // sizes 1e-6 .. 1e3 in a 100 box
        {"soup_small", [] { return makeSoupScene(2000, 2, 1e-3f, 1.0f, 10.0f); }},
        {"default", [] { return makeDefaultScene(); }},
        {"closed", [] { return makeClosedMeshesScene(); }},
        {"terrain", [] { return makeTerrainScene(48, 3); }},
        {"coincident", [] { return makeCoincidentScene(4); }},
        {"centroids_line", [] { return makeCentroidsOnLineScene(1500, 5); }},
        {"centroids_plane", [] { return makeCentroidsOnPlaneScene(1500, 6); }},
        {"centroids_point", [] { return makeCentroidsAtPointScene(300, 7); }},
        {"tiny0", [] { return makeTinyScene(0, 8); }},
        {"tiny1", [] { return makeTinyScene(1, 9); }},
        {"tiny2", [] { return makeTinyScene(2, 10); }},
        {"tiny3", [] { return makeTinyScene(3, 11); }},
        {"degenerate_mix", [] { return makeDegenerateMixScene(2000, 12); }},
    };
    return scenes;
}

// ---------------------------------------------------------------------------------------------

std::string describe(const Ray& r) {
    return fmt::format("org=({:.9g}, {:.9g}, {:.9g}) dir=({:.9g}, {:.9g}, {:.9g}) t in [{:.9g}, {:.9g}]", r.org.x,
                       r.org.y, r.org.z, r.dir.x, r.dir.y, r.dir.z, r.tmin, r.tmax);
}

std::string describe(const Hit& h) {
    if (!h.found()) return "miss";
    return fmt::format("t={:.9g} prim={} u={:.9g} v={:.9g}", h.t, h.primitive, h.u, h.v);
}

std::string describe(const OracleHit& h) {
    if (!h.found()) return "miss";
    return fmt::format("t={:.17g} prim={} u={:.9g} v={:.9g}", h.t, h.primitive, h.u, h.v);
}

Reference computeReference(const Accelerator& naive, const Oracle& oracle, std::span<const Ray> rays) {
    Reference ref;
    ref.naive.resize(rays.size());
    ref.naiveVerdict.resize(rays.size());
    ref.naiveReason.resize(rays.size());
    ref.oracle.resize(rays.size());
    QueryCounters counters;
    for (size_t i = 0; i < rays.size(); ++i) {
        Hit hit;
        if (!naive.findNearest(rays[i], hit, counters)) hit = Hit{};
        ref.naive[i] = hit;
        ref.oracle[i] = oracle.nearest(rays[i]);
        Judgement j = oracle.judge(rays[i], hit, ref.oracle[i]);
        ref.naiveVerdict[i] = j.verdict;
        ref.naiveReason[i] = std::move(j.reason);
    }
    return ref;
}

Reference computeOracleReference(const Oracle& oracle, std::span<const Ray> rays) {
    Reference ref;
    ref.oracle.resize(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) ref.oracle[i] = oracle.nearest(rays[i]);
    return ref;
}

std::string ComparisonReport::summary() const {
    std::string s = fmt::format(
        "{} rays: accel {} hits, naive {} hits; {} disagreements with naive (accelerator wrong {}, naive wrong {}, "
        "both wrong {}, ambiguous {}); judged wrong overall: accelerator {}, naive {}; accelerator != oracle on {} "
        "rays; return/hit contract violations {}; isOccluded != findNearest {} (+{} skipped as ties at an interval "
        "end); isOccluded true below the nearest hit {}; queries miscounted {}",
        rays, accelHits, naiveHits, disagreements, accelOnlyWrong, naiveOnlyWrong, bothWrong, ambiguous, accelWrong,
        naiveWrong, accelVsOracle, returnMismatch, occlusionMismatch, occlusionTies, shrunkOcclusion,
        queriesMiscounted);
    for (const std::string& e : examples) s += "\n    " + e;
    for (const std::string& e : occlusionExamples) s += "\n    " + e;
    return s;
}

ComparisonReport compareWithReference(const Accelerator& accel, const Reference& ref, const Oracle& oracle,
                                      std::span<const Ray> rays, size_t maxExamples, bool occlusion) {
    ComparisonReport report;
    report.rays = rays.size();
    auto exampleIn = [&](std::vector<std::string>& list, size_t i, const std::string& what) {
        if (list.size() < maxExamples) list.push_back(fmt::format("ray #{} {}: {}", i, describe(rays[i]), what));
    };
    auto example = [&](size_t i, const std::string& what) { exampleIn(report.examples, i, what); };
    auto occlusionExample = [&](size_t i, const std::string& what) { exampleIn(report.occlusionExamples, i, what); };
    // Without naive's answers (computeOracleReference), naive is the oracle.
    const bool withNaive = !ref.naive.empty();
    // Without the oracle's answers (an empty Reference), the interface contract alone.
    const bool judged = !ref.oracle.empty();
    const Hit sentinel{-12345.0f, 0xDEADBEEFu, 7.0f, 9.0f};
    for (size_t i = 0; i < rays.size(); ++i) {
        const Ray& ray = rays[i];
        QueryCounters counters;
        Hit hit = sentinel;
        const bool found = accel.findNearest(ray, hit, counters);
        if (counters.queries != 1) {
            ++report.queriesMiscounted;
            example(i, fmt::format("findNearest counted {} queries", counters.queries));
        }
        if (found ? !hit.found()
                  : (hit.t != sentinel.t || hit.primitive != sentinel.primitive || hit.u != sentinel.u ||
                     hit.v != sentinel.v)) {
            ++report.returnMismatch;
            example(i, fmt::format("findNearest returned {} with hit {}", found, describe(hit)));
        }
        const Hit a = found ? hit : Hit{};
        report.accelHits += a.found();
        if (judged) {
            const Hit n = withNaive ? ref.naive[i] : ref.oracle[i].toHit();
            report.naiveHits += n.found();
            const bool naiveWrong = withNaive && ref.naiveVerdict[i] == Verdict::Wrong;
            report.naiveWrong += naiveWrong;

            const Judgement ja = oracle.judge(ray, a, ref.oracle[i]);
            const bool accelWrong = ja.verdict == Verdict::Wrong;
            report.accelWrong += accelWrong;
            report.accelVsOracle += !agree(a, ref.oracle[i].toHit());
            if (!agree(a, n)) {
                ++report.disagreements;
                if (accelWrong && naiveWrong) ++report.bothWrong;
                else if (accelWrong) ++report.accelOnlyWrong;
                else if (naiveWrong) ++report.naiveOnlyWrong;
                else ++report.ambiguous;
            }
            if (accelWrong && !withNaive)
                example(i, fmt::format("structure {} [{}: {}]; reference {}", describe(a), verdictName(ja.verdict), ja.reason,
                                       describe(ref.oracle[i])));
            else if (accelWrong || naiveWrong)
                example(i, fmt::format("accelerator {} [{}: {}]; naive {} [{}{}{}]; oracle {}", describe(a),
                                       verdictName(ja.verdict), ja.reason, describe(n), verdictName(ref.naiveVerdict[i]),
                                       naiveWrong ? ": " : "", naiveWrong ? ref.naiveReason[i] : "",
                                       describe(ref.oracle[i])));
        }
        if (!occlusion) continue;

        // isOccluded must answer "is there a hit" exactly as findNearest did, except for a hit
        // within hitsAgree's tolerance of an interval end.
        QueryCounters occCounters;
        const bool occluded = accel.isOccluded(ray, occCounters);
        if (occCounters.queries != 1) {
            ++report.queriesMiscounted;
            ++report.occludedMiscounted;
            occlusionExample(i, fmt::format("isOccluded counted {} queries", occCounters.queries));
        }
        if (occluded != a.found()) {
            const float tol = 1e-4f * std::max(1.0f, std::abs(a.t));
            const bool tie = a.found() && (std::abs(a.t - ray.tmax) <= tol || std::abs(a.t - ray.tmin) <= tol);
            if (tie) {
                ++report.occlusionTies;
            } else {
                ++report.occlusionMismatch;
                occlusionExample(i, fmt::format("isOccluded = {} but findNearest found {}", occluded, describe(a)));
            }
        }
        // Nothing can block the ray before its nearest hit: with tmax just below the nearest t
        // (by 1e-3 relative, far more than any rounding of t), isOccluded must be false. For
        // accelerators that run the same float triangle test in both queries this is exact.
        if (a.found() && a.t > 0.0f && std::isfinite(a.t)) {
            Ray shorter = ray;
            shorter.tmax = a.t * (1.0f - 1e-3f);
            if (shorter.tmin <= shorter.tmax && accel.isOccluded(shorter, occCounters)) {
                ++report.shrunkOcclusion;
                occlusionExample(i, fmt::format("isOccluded true with tmax = {:.9g} below the nearest hit {}", shorter.tmax,
                                       describe(a)));
            }
        }
    }
    return report;
}

ComparisonReport compareWithNaive(const Accelerator& accel, const Accelerator& naive, const Oracle& oracle,
                                  std::span<const Ray> rays, size_t maxExamples) {
    return compareWithReference(accel, computeReference(naive, oracle, rays), oracle, rays, maxExamples);
}

}  // namespace bvhlab::check
