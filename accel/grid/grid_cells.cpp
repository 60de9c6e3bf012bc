#include "accel/grid/grid_cells.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace bvhlab::grid {

uint64_t GridCells::emptyCells() const {
    uint64_t empty = 0;
    for (size_t c = 0; c + 1 < cellStart.size(); ++c) empty += cellStart[c] == cellStart[c + 1];
    return empty;
}

size_t GridCells::maxCellReferences() const {
    size_t most = 0;
    for (size_t c = 0; c + 1 < cellStart.size(); ++c) most = std::max<size_t>(most, cellStart[c + 1] - cellStart[c]);
    return most;
}

Bounds3 primitiveBounds(const PrimitiveSet& prims) {
    Bounds3 box;
    for (uint32_t p : prims.validTriangles()) box.extend(prims.triangles[p].bounds());
    for (uint32_t p : prims.validQuadrics()) box.extend(boundsOf(prims.quadric(p)));
    return box;
}

namespace {

// Projections of the triangle (relative to the box centre) and the box's half extent on `axis`
// overlap (touching counts).
bool overlapOnAxis(const DVec3& axis, const DVec3& a, const DVec3& b, const DVec3& c, const DVec3& half) {
    const double pa = glm::dot(axis, a), pb = glm::dot(axis, b), pc = glm::dot(axis, c);
    const double r = half.x * std::abs(axis.x) + half.y * std::abs(axis.y) + half.z * std::abs(axis.z);
    const double lo = std::min({pa, pb, pc}), hi = std::max({pa, pb, pc});
    // A small relative slack for the rounding of the products above.
    const double slack = 1e-12 * (std::abs(lo) + std::abs(hi) + r);
    return !(lo > r + slack || hi < -r - slack);
}

}  // namespace

bool triangleOverlapsBox(const Triangle& tri, const DVec3& lo, const DVec3& hi) {
    const DVec3 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    const DVec3 a = DVec3(tri.v0) - centre, b = DVec3(tri.v1) - centre, c = DVec3(tri.v2) - centre;
    // The box's axes.
    for (int k = 0; k < 3; ++k) {
        if (std::min({a[k], b[k], c[k]}) > half[k] || std::max({a[k], b[k], c[k]}) < -half[k]) return false;
    }
    // The triangle's normal (zero for a sliver: no separation claimed).
    const DVec3 e0 = b - a, e1 = c - b, e2 = a - c;
    if (!overlapOnAxis(glm::cross(e0, e1), a, b, c, half)) return false;
    // Edge x box axis.
    const DVec3 edges[3] = {e0, e1, e2};
    for (const DVec3& e : edges) {
        for (int k = 0; k < 3; ++k) {
            DVec3 unit(0.0);
            unit[k] = 1.0;
            if (!overlapOnAxis(glm::cross(e, unit), a, b, c, half)) return false;
        }
    }
    return true;
}

bool sphereOverlapsBox(const Sphere& sphere, const DVec3& lo, const DVec3& hi) {
    const DVec3 c(sphere.centre);
    const DVec3 nearest = glm::clamp(c, lo, hi);
    const DVec3 d = c - nearest;
    const double r = std::abs(double(sphere.radius));
    return glm::dot(d, d) <= r * r * (1.0 + 1e-9);
}

namespace {

struct CellRange {
    int lo[3], hi[3];
    uint64_t count() const {
        return uint64_t(hi[0] - lo[0] + 1) * uint64_t(hi[1] - lo[1] + 1) * uint64_t(hi[2] - lo[2] + 1);
    }
};

class Builder {
public:
    Builder(const PrimitiveSet& prims, GridCells& grid, bool exact) : prims_(prims), g_(grid), exact_(exact) {
        const double magnitude = std::max({std::abs(g_.lower.x), std::abs(g_.lower.y), std::abs(g_.lower.z),
                                           std::abs(g_.upper.x), std::abs(g_.upper.y), std::abs(g_.upper.z)});
        for (int a = 0; a < 3; ++a) margin_[a] = kCellMargin * g_.cellSize[a] + 1e-6 * magnitude;
    }

    // The cells the primitive's box (enlarged by the margin) covers.
    CellRange range(uint32_t prim) const {
        const Bounds3 b = prims_.kind(prim) == PrimitiveKind::Triangle ? prims_.triangles[prim].bounds()
                                                                       : boundsOf(prims_.quadric(prim));
        CellRange r;
        for (int a = 0; a < 3; ++a) {
            r.lo[a] = cellOf(a, double(b.lower[a]) - margin_[a]);
            r.hi[a] = cellOf(a, double(b.upper[a]) + margin_[a]);
        }
        return r;
    }

    bool overlaps(uint32_t prim, int x, int y, int z) const {
        if (!exact_) return true;  // the cell is in the range of the primitive's box
        const DVec3 lo = g_.lower + DVec3(x, y, z) * g_.cellSize - margin_;
        const DVec3 hi = g_.lower + DVec3(x + 1, y + 1, z + 1) * g_.cellSize + margin_;
        switch (prims_.kind(prim)) {
            case PrimitiveKind::Triangle:
                return triangleOverlapsBox(prims_.triangles[prim], lo, hi);
            case PrimitiveKind::Sphere:
                return sphereOverlapsBox(*prims_.quadric(prim).sphere(), lo, hi);
            case PrimitiveKind::Cone:
            default:
                return true;  // its box covers the cell (range())
        }
    }

    template <typename Visit>
    void forEachCell(uint32_t prim, Visit&& visit) const {
        const CellRange r = range(prim);
        for (int z = r.lo[2]; z <= r.hi[2]; ++z)
            for (int y = r.lo[1]; y <= r.hi[1]; ++y)
                for (int x = r.lo[0]; x <= r.hi[0]; ++x)
                    if (overlaps(prim, x, y, z)) visit(g_.cellIndex(x, y, z));
    }

private:
    int cellOf(int axis, double coordinate) const {
        const double c = std::floor((coordinate - g_.lower[axis]) * g_.inverseCellSize[axis]);
        if (!(c >= 0.0)) return 0;
        return int(std::min(c, double(g_.res[axis] - 1)));
    }

    const PrimitiveSet& prims_;
    GridCells& g_;
    bool exact_;
    DVec3 margin_;
};

void setResolution(GridCells& g, const GridResolution& res) {
    g.res = res;
    for (int a = 0; a < 3; ++a) {
        g.cellSize[a] = (g.upper[a] - g.lower[a]) / res[a];
        g.inverseCellSize[a] = 1.0 / g.cellSize[a];
    }
}

}  // namespace

GridCells buildGridCells(const PrimitiveSet& prims, const GridParameters& parameters) {
    GridCells g;
    const Bounds3 box = primitiveBounds(prims);
    if (prims.valid.empty() || box.isEmpty()) return g;
    const DVec3 lower(box.lower), upper(box.upper);
    const DVec3 extent = upper - lower;
    // Padded so that no axis is of zero width and the box's faces lie off the primitives.
    const double longest = std::max({extent.x, extent.y, extent.z});
    const double magnitude = std::max({std::abs(lower.x), std::abs(lower.y), std::abs(lower.z), std::abs(upper.x),
                                       std::abs(upper.y), std::abs(upper.z)});
    const double pad = 1e-5 * longest + 1e-5 * magnitude + 1e-30;
    g.lower = lower - pad;
    g.upper = upper + pad;
    const double objects = parameters.objects > 0.0 ? parameters.objects : double(prims.valid.size());
    const double density = parameters.density;

    const uint64_t budget = std::max(kMinReferenceBudget, kReferencesPerPrimitive * uint64_t(prims.valid.size()));
    double d = density;
    for (;;) {
        if (parameters.fixed) {
            const double scale = std::cbrt(d / density);
            const GridResolution& f = *parameters.fixed;
            setResolution(
                g, {std::max(1, int(f.x * scale)), std::max(1, int(f.y * scale)), std::max(1, int(f.z * scale))});
        } else {
            setResolution(g, gridResolution(parameters.setting, d, objects, extent));
        }
        bool fits = g.cells() <= kMaxCells;
        if (fits) {
            const Builder builder(prims, g, parameters.exactOverlap);
            uint64_t bound = 0;
            for (uint32_t p : prims.valid) {
                bound += builder.range(p).count();
                if (bound > budget) break;
            }
            fits = bound <= budget;
        }
        if (fits || g.cells() == 1) break;
        d *= 0.5;
    }
    g.densityUsed = d;

    const Builder builder(prims, g, parameters.exactOverlap);
    std::vector<uint32_t> count(g.cells() + 1, 0);
    for (uint32_t p : prims.valid) builder.forEachCell(p, [&](size_t c) { ++count[c + 1]; });
    for (size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
    g.cellStart = count;
    g.refs.resize(g.cellStart.back());
    for (uint32_t p : prims.valid) builder.forEachCell(p, [&](size_t c) { g.refs[count[c]++] = p; });
    return g;
}

}  // namespace bvhlab::grid
