#include "framework/scene/polygon_triangulation.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace bvhlab {

std::string_view describe(PolygonProblem problem) {
    switch (problem) {
        case PolygonProblem::None:
            return "triangulated";
        case PolygonProblem::ZeroArea:
            return "of zero area (fewer than three distinct corners, or all on one line)";
        case PolygonProblem::NotPlanar:
            return "not planar";
        case PolygonProblem::SelfIntersecting:
            return "self-intersecting (edges cross, touch or double back)";
        case PolygonProblem::NotFinite:
            return "with a NaN or infinite coordinate";
        case PolygonProblem::TooComplex:
            return "non-convex with too many corners to triangulate in bounded time";
    }
    return "?";
}

namespace {

double cross(const glm::dvec2& u, const glm::dvec2& v) { return u.x * v.y - u.y * v.x; }

// Closed segments pq and rs share a point.
bool segmentsMeet(const glm::dvec2& p, const glm::dvec2& q, const glm::dvec2& r, const glm::dvec2& s) {
    if (std::max(p.x, q.x) < std::min(r.x, s.x) || std::max(r.x, s.x) < std::min(p.x, q.x) ||
        std::max(p.y, q.y) < std::min(r.y, s.y) || std::max(r.y, s.y) < std::min(p.y, q.y))
        return false;
    const double d1 = cross(q - p, r - p), d2 = cross(q - p, s - p);
    const double d3 = cross(s - r, p - r), d4 = cross(s - r, q - r);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
    // Touching or collinear: an end on the other segment (the boxes overlap, checked above).
    const auto onSegment = [](const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& x, double side) {
        return side == 0 && std::min(a.x, b.x) <= x.x && x.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= x.y &&
               x.y <= std::max(a.y, b.y);
    };
    return onSegment(p, q, r, d1) || onSegment(p, q, s, d2) || onSegment(r, s, p, d3) || onSegment(r, s, q, d4);
}

}  // namespace

double PolygonTriangulator::orient(uint32_t a, uint32_t b, uint32_t c) const {
    return cross(points_[b] - points_[a], points_[c] - points_[a]);
}

PolygonProblem PolygonTriangulator::triangulate(std::span<const Vec3> positions, std::span<const uint32_t> corners) {
    triangles_.clear();
    earClipped_ = false;
    corners_.clear();
    for (const uint32_t c : corners) {
        if (corners_.empty() || positions[c] != positions[corners_.back()]) corners_.push_back(c);
    }
    while (corners_.size() > 1 && positions[corners_.back()] == positions[corners_.front()]) corners_.pop_back();
    for (const uint32_t c : corners_) {
        if (!isFinite(positions[c])) return PolygonProblem::NotFinite;
    }
    if (corners_.size() < 3) return PolygonProblem::ZeroArea;
    if (corners_.size() == 3) {  // a triangle covers itself; Scene::finalize judges its area
        triangles_.emplace_back(corners_[0], corners_[1], corners_[2]);
        return PolygonProblem::None;
    }

    PolygonProblem problem = PolygonProblem::None;
    if (!project(positions, problem)) return problem;
    if (isConvex()) {
        for (size_t i = 1; i + 1 < corners_.size(); ++i)
            triangles_.emplace_back(corners_[0], corners_[i], corners_[i + 1]);
        return PolygonProblem::None;
    }
    earClipped_ = true;
    if (corners_.size() > kMaxNonConvexCorners) return PolygonProblem::TooComplex;
    if (!isSimple()) return PolygonProblem::SelfIntersecting;
    problem = earClip();
    if (problem != PolygonProblem::None) triangles_.clear();
    return problem;
}

// The corners in the plane of the Newell normal (the axis it is largest along dropped),
// mirrored if need be so that they run counter-clockwise; false with the problem if the
// polygon has no area or is not planar.
bool PolygonTriangulator::project(std::span<const Vec3> positions, PolygonProblem& problem) {
    const size_t n = corners_.size();
    DVec3 normal{0.0}, centroid{0.0}, lower{positions[corners_[0]]}, upper = lower;
    double largestCoordinate = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const DVec3 a{positions[corners_[i]]}, b{positions[corners_[(i + 1) % n]]};
        normal += DVec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
        centroid += a;
        lower = glm::min(lower, a);
        upper = glm::max(upper, a);
        largestCoordinate = std::max({largestCoordinate, std::abs(a.x), std::abs(a.y), std::abs(a.z)});
    }
    centroid /= double(n);
    const double diagonal = glm::length(upper - lower);
    // What rounding the corners to float can make of twice an area that is 0.
    const double noise = 0x1p-20 * largestCoordinate * diagonal;
    // The largest triangle of the fan from the first corner: none if all corners are on a line.
    const DVec3 first{positions[corners_[0]]};
    DVec3 widest{0.0};
    for (size_t i = 1; i + 1 < n; ++i) {
        const DVec3 c = glm::cross(DVec3(positions[corners_[i]]) - first, DVec3(positions[corners_[i + 1]]) - first);
        if (glm::length(c) > glm::length(widest)) widest = c;
    }
    if (!(glm::length(widest) > noise)) {
        problem = PolygonProblem::ZeroArea;
        return false;
    }
    // A boundary whose signed areas cancel (a bow tie) has no Newell normal: its plane, if it
    // has one, is that of the largest fan triangle.
    const bool cancels = !(glm::length(normal) > noise);
    const DVec3 planeNormal = cancels ? widest : normal;
    const DVec3 unit = glm::normalize(planeNormal);
    // Six printed digits move a coordinate by up to 5e-6 of its magnitude.
    const double tolerance = kPlanarTolerance * diagonal + 1e-5 * largestCoordinate;
    for (const uint32_t c : corners_) {
        if (std::abs(glm::dot(DVec3(positions[c]) - centroid, unit)) > tolerance) {
            problem = PolygonProblem::NotPlanar;
            return false;
        }
    }
    if (cancels) {
        problem = PolygonProblem::SelfIntersecting;
        return false;
    }

    const int axis = std::abs(normal.x) >= std::abs(normal.y) && std::abs(normal.x) >= std::abs(normal.z) ? 0
                     : std::abs(normal.y) >= std::abs(normal.z)                                           ? 1
                                                                                                          : 2;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    // The Newell component along `axis` is twice the signed area in (u, v).
    const double mirror = normal[axis] > 0 ? 1.0 : -1.0;
    points_.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const DVec3 p = DVec3(positions[corners_[i]]) - centroid;
        points_[i] = {p[u], mirror * p[v]};
    }
    return true;
}

// Every corner turns left or goes straight on, and the boundary winds around once.
bool PolygonTriangulator::isConvex() const {
    const uint32_t n = uint32_t(points_.size());
    double turning = 0.0;
    for (uint32_t i = 0; i < n; ++i) {
        const glm::dvec2 in = points_[i] - points_[(i + n - 1) % n];
        const glm::dvec2 out = points_[(i + 1) % n] - points_[i];
        const double turn = cross(in, out), straight = glm::dot(in, out);
        if (turn < -1e-12 * glm::length(in) * glm::length(out) || (turn <= 0 && straight < 0)) return false;
        turning += std::atan2(turn, straight);
    }
    return std::abs(turning - 2.0 * std::numbers::pi) < 1e-6;
}

// No two edges meet but neighbours at their shared corner, and no edge doubles back.
bool PolygonTriangulator::isSimple() const {
    const size_t n = points_.size();
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec2 &p = points_[i], &q = points_[(i + 1) % n];
        // The next edge, from q: it must not run back along this one.
        const glm::dvec2& r = points_[(i + 2) % n];
        if (cross(p - q, r - q) == 0 && glm::dot(p - q, r - q) > 0) return false;
        for (size_t j = i + 2; j < n; ++j) {
            if (i == 0 && j == n - 1) continue;  // the edge before edge 0
            if (segmentsMeet(p, q, points_[j], points_[(j + 1) % n])) return false;
        }
    }
    return true;
}

// A corner whose triangle with its two neighbours turns left and holds no other remaining
// corner, on its boundary included (so that no clip leaves a corner on the new edge).
bool PolygonTriangulator::isEar(uint32_t i) {
    const uint32_t a = prev_[i], c = next_[i];
    if (!(orient(a, i, c) > 0)) return false;
    for (uint32_t j = next_[c]; j != a; j = next_[j]) {
        ++earTests_;
        if (orient(a, i, j) >= 0 && orient(i, c, j) >= 0 && orient(c, a, j) >= 0) return false;
    }
    return true;
}

PolygonProblem PolygonTriangulator::earClip() {
    const uint32_t n = uint32_t(points_.size());
    prev_.resize(n);
    next_.resize(n);
    ear_.resize(n);
    earTests_ = 0;
    for (uint32_t i = 0; i < n; ++i) {
        prev_[i] = (i + n - 1) % n;
        next_[i] = (i + 1) % n;
    }
    for (uint32_t i = 0; i < n; ++i) ear_[i] = isEar(i);

    uint32_t remaining = n, i = 0, sinceClip = 0;
    bool refreshed = false;  // every flag recomputed since the last clip
    while (remaining > 3) {
        if (earTests_ > kMaxEarTests) return PolygonProblem::TooComplex;
        if (ear_[i] && isEar(i)) {
            const uint32_t a = prev_[i], c = next_[i];
            triangles_.emplace_back(corners_[a], corners_[i], corners_[c]);
            next_[a] = c;
            prev_[c] = a;
            --remaining;
            ear_[a] = isEar(a);
            ear_[c] = isEar(c);
            i = c;
            sinceClip = 0;
            refreshed = false;
            continue;
        }
        ear_[i] = false;
        i = next_[i];
        if (++sinceClip <= remaining) continue;
        // A whole round without an ear: the flags of corners away from the clips may be stale
        // (a clipped corner was the only one inside their triangle). Once they are fresh, a
        // round without an ear leaves a boundary of zero area, or numbers too close to call.
        if (refreshed) {
            double twiceArea = 0.0, scale = 0.0;
            for (uint32_t k = 0, j = i; k < remaining; ++k, j = next_[j]) {
                twiceArea += cross(points_[j], points_[next_[j]]);
                scale += glm::length(points_[j] - points_[next_[j]]);
            }
            return std::abs(twiceArea) <= 1e-12 * scale * scale ? PolygonProblem::None
                                                                : PolygonProblem::SelfIntersecting;
        }
        for (uint32_t k = 0, j = i; k < remaining; ++k, j = next_[j]) ear_[j] = isEar(j);
        refreshed = true;
        sinceClip = 0;
    }
    if (orient(prev_[i], i, next_[i]) > 0) triangles_.emplace_back(corners_[prev_[i]], corners_[i], corners_[next_[i]]);
    return PolygonProblem::None;
}

}  // namespace bvhlab
