#include "accel/verify/oracle.h"

#include <bvhlab/triangle.h>
#include <glm/glm.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bvhlab::verify {

namespace {

using D3 = glm::dvec3;

constexpr double kInf = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// Error model of the float watertight test (<bvhlab/triangle.h>), used by the judge.
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
    D3 normal;          // unnormalised, cross(v1 - v0, v2 - v0)
    double normalLen;   // twice the area
    double cosine;      // |cos| of the angle between the ray and the normal
    double tolLateral;  // absolute distance
    double tolT;        // in units of t
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
    const double longest = std::max({glm::length(g.v1 - g.v0), glm::length(g.v2 - g.v1), glm::length(g.v0 - g.v2)});
    return g.normalLen / longest;
}

}  // namespace

const char* verdictName(Verdict v) {
    switch (v) {
        case Verdict::Right:
            return "right";
        case Verdict::Ambiguous:
            return "ambiguous";
        case Verdict::Wrong:
            return "WRONG";
    }
    return "?";
}

Oracle::Oracle(const PrimitiveSet& prims) : prims_(prims), valid_(prims.triangles.size(), 0) {
    if (prims.hasQuadrics())
        throw std::invalid_argument(
            "Oracle: triangles only (scenes with spheres and cones: test_mixed_primitives.cpp)");
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
            return {Verdict::Wrong,
                    fmt::format("t = {:.9g} is outside [{:.9g}, {:.9g}]", answer.t, ray.tmin, ray.tmax)};
        claimed = geometryOf(prims_.triangles[p], ray);
        const D3 q = org + double(answer.t) * dir;
        const double dist = glm::length(q - closestPointOnTriangle(q, claimed.v0, claimed.v1, claimed.v2));
        const double c = std::max(claimed.cosine, 1e-300);
        const double tol = claimed.tolLateral * (1.0 + 1.0 / c) + claimed.tolT * dirLen;
        if (dist > tol)
            return {Verdict::Wrong, fmt::format("the point at t = {:.9g} is {:.3g} from triangle {} (bound {:.3g})",
                                                answer.t, dist, p, tol)};
        if (!(answer.u >= -1e-6f && answer.v >= -1e-6f && answer.u + answer.v <= 1.0f + 1e-5f))
            return {Verdict::Wrong,
                    fmt::format("u = {:.9g}, v = {:.9g} are not barycentric weights", answer.u, answer.v)};
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
        if (!answer.found()) return {Verdict::Wrong, fmt::format("missed an unambiguous hit: {}", describe(h))};
        const double margin = g.tolT + claimed.tolT + 1e-4 * std::max(1.0, std::abs(double(answer.t)));
        if (h.t < double(answer.t) - margin)
            return {Verdict::Wrong, fmt::format("missed an unambiguous closer hit: {}", describe(h))};
        break;  // hits are sorted: later ones are farther
    }
    return {Verdict::Ambiguous, fmt::format("differs from the oracle ({}) within error bounds", describe(nearestHit))};
}

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

}  // namespace bvhlab::verify
