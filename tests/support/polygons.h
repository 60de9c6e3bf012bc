// Non-convex test polygons (a star, a comb, a square with a notch, a gear of 144 corners as
// SPD's gears), Haines' crossings test to decide what they cover, and NFF text that places
// them in space: shared by the triangulation, reader and accelerator tests.
#pragma once

#include <bvhlab/math.h>
#include <glm/glm.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace bvhlab::test {

using Polygon2 = std::vector<glm::dvec2>;

// Counter-clockwise, `points` tips between radii 1 and `inner`.
inline Polygon2 starPolygon(int points = 7, double inner = 0.35) {
    Polygon2 p;
    for (int i = 0; i < 2 * points; ++i) {
        const double a = std::numbers::pi * i / points, r = i % 2 ? inner : 1.0;
        p.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    return p;
}

// A bar from (0, 0) to (2, 0.3) with `teeth` teeth of height 1 standing on it, gaps between.
inline Polygon2 combPolygon(int teeth = 6) {
    Polygon2 p{{0.0, 0.0}, {2.0, 0.0}};
    const double w = 2.0 / (2 * teeth - 1);
    for (int t = teeth - 1; t >= 0; --t) {
        const double x0 = 2 * t * w, x1 = x0 + w;
        p.emplace_back(x1, 1.3);
        p.emplace_back(x0, 1.3);
        if (t > 0) {
            p.emplace_back(x0, 0.3);
            p.emplace_back(x0 - w, 0.3);
        }
    }
    return p;
}

// The unit square with a notch cut into its top edge, and a corner on the notch's floor
// collinear with its neighbours.
inline Polygon2 notchedSquare() {
    return {{0, 0}, {1, 0}, {1, 1}, {0.6, 1}, {0.6, 0.3}, {0.5, 0.3}, {0.4, 0.3}, {0.4, 1}, {0, 1}};
}

// 36 teeth of four corners each, as the faces of SPD's gears: 144 corners.
inline Polygon2 gearPolygon() {
    Polygon2 p;
    const int teeth = 36;
    for (int t = 0; t < teeth; ++t) {
        const double a = 2 * std::numbers::pi * t / teeth, step = 2 * std::numbers::pi / teeth;
        for (const auto& [da, r] : {std::pair{0.0, 0.8}, {0.25, 1.0}, {0.5, 1.0}, {0.75, 0.8}})
            p.emplace_back(r * std::cos(a + da * step), r * std::sin(a + da * step));
    }
    return p;
}

// Haines' crossings test: is q inside the polygon (even-odd)?
inline bool insidePolygon(const Polygon2& p, const glm::dvec2& q) {
    bool inside = false;
    for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
        if ((p[i].y > q.y) != (p[j].y > q.y) && q.x < (p[j].x - p[i].x) * (q.y - p[i].y) / (p[j].y - p[i].y) + p[i].x)
            inside = !inside;
    }
    return inside;
}

// The distance from q to the polygon's boundary.
inline double distanceToBoundary(const Polygon2& p, const glm::dvec2& q) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
        const glm::dvec2 e = p[i] - p[j];
        const double s = std::clamp(glm::dot(q - p[j], e) / glm::dot(e, e), 0.0, 1.0);
        best = std::min(best, glm::length(q - (p[j] + s * e)));
    }
    return best;
}

inline double polygonArea(const Polygon2& p) {
    double twice = 0.0;
    for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) twice += p[j].x * p[i].y - p[i].x * p[j].y;
    return 0.5 * twice;
}

// A plane in space: the polygon's (x, y) map to origin + x * u + y * v.
struct PolygonPlane {
    DVec3 origin{0.0}, u{1, 0, 0}, v{0, 1, 0};
    DVec3 at(const glm::dvec2& q) const { return origin + q.x * u + q.y * v; }
    DVec3 normal() const { return glm::normalize(glm::cross(u, v)); }
};

// The polygon as an NFF "p" entity in `plane`.
inline std::string nffPolygon(const Polygon2& p, const PolygonPlane& plane) {
    std::string text = fmt::format("p {}\n", p.size());
    for (const glm::dvec2& q : p) {
        const DVec3 x = plane.at(q);
        text += fmt::format("{:.9g} {:.9g} {:.9g}\n", x.x, x.y, x.z);
    }
    return text;
}

}  // namespace bvhlab::test
