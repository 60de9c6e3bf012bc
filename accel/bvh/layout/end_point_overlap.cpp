#include "accel/bvh/layout/end_point_overlap.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <vector>

namespace bvhlab {

namespace {

using DVec = glm::dvec3;

// A convex polygon: a triangle clipped by up to six planes has at most nine corners.
struct Polygon {
    std::array<DVec, 9> p;
    int n = 0;
};

// Keeps the part of `in` where sign * (x[axis] - plane) <= 0 (Sutherland-Hodgman).
Polygon clipByPlane(const Polygon& in, int axis, double plane, double sign) {
    Polygon out;
    for (int i = 0; i < in.n; ++i) {
        const DVec& a = in.p[i];
        const DVec& b = in.p[(i + 1) % in.n];
        const double da = sign * (a[axis] - plane), db = sign * (b[axis] - plane);
        if (da <= 0) out.p[out.n++] = a;
        if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
            DVec x = a + (b - a) * (da / (da - db));
            x[axis] = plane;  // exactly on the plane
            out.p[out.n++] = x;
        }
    }
    return out;
}

double polygonArea(const Polygon& poly) {
    DVec sum(0.0);
    for (int i = 1; i + 1 < poly.n; ++i) sum += glm::cross(poly.p[i] - poly.p[0], poly.p[i + 1] - poly.p[0]);
    return 0.5 * glm::length(sum);
}

bool inside(const Bounds3& inner, const Bounds3& outer) {
    for (int a = 0; a < 3; ++a)
        if (inner.lower[a] < outer.lower[a] || inner.upper[a] > outer.upper[a]) return false;
    return true;
}

bool overlaps(const Bounds3& a, const Bounds3& b) {
    for (int a3 = 0; a3 < 3; ++a3)
        if (a.upper[a3] < b.lower[a3] || b.upper[a3] < a.lower[a3]) return false;
    return true;
}

double triangleArea(const Triangle& t) {
    return 0.5 * glm::length(glm::cross(DVec(t.v1) - DVec(t.v0), DVec(t.v2) - DVec(t.v0)));
}

// Per node, the leaf slots of its subtree: [first, end). Children follow their parent in the
// layout, so one backward pass fills them.
struct SlotRange {
    uint32_t first, end;
};

std::vector<SlotRange> subtreeSlots(std::span<const BvhNode> nodes) {
    std::vector<SlotRange> slots(nodes.size());
    for (size_t i = nodes.size(); i-- > 0;) {
        if (i == 1) continue;  // the padding slot
        const BvhNode& n = nodes[i];
        slots[i] = n.isLeaf() ? SlotRange{n.index, n.index + n.count}
                              : SlotRange{slots[n.index].first, slots[n.index + 1].end};
    }
    return slots;
}

}  // namespace

double clippedArea(const Triangle& t, const Bounds3& box) {
    Polygon poly;
    poly.p[0] = DVec(t.v0), poly.p[1] = DVec(t.v1), poly.p[2] = DVec(t.v2);
    poly.n = 3;
    for (int a = 0; a < 3 && poly.n >= 3; ++a) {
        poly = clipByPlane(poly, a, box.lower[a], -1.0);
        if (poly.n >= 3) poly = clipByPlane(poly, a, box.upper[a], 1.0);
    }
    return poly.n >= 3 ? polygonArea(poly) : 0.0;
}

std::optional<double> endPointOverlap(std::span<const BvhNode> nodes, std::span<const Triangle> leafTriangles,
                                      double cTraversal, double cIntersect, int threads) {
    if (nodes.empty()) return 0.0;
    const std::vector<SlotRange> slots = subtreeSlots(nodes);
    struct Sums {
        double overlap = 0.0, area = 0.0;
    };
    // The overlap of triangle `slot` with the boxes of the nodes it does not belong to.
    const auto overlapOf = [&](uint32_t slot, std::vector<uint32_t>& stack, uint64_t& visits) {
        const Triangle& t = leafTriangles[slot];
        const Bounds3 tb = t.bounds();
        double sum = 0.0;
        stack.assign(1, 0);
        while (!stack.empty()) {
            const BvhNode& n = nodes[stack.back()];
            const SlotRange own = slots[stack.back()];
            stack.pop_back();
            ++visits;
            const Bounds3 box = n.box();
            if (!overlaps(tb, box)) continue;
            if (slot < own.first || slot >= own.end) {
                const double area = inside(tb, box) ? triangleArea(t) : clippedArea(t, box);
                if (area == 0.0) continue;  // nor any inside this box
                sum += (n.isLeaf() ? cIntersect : cTraversal) * area;
            }
            if (!n.isLeaf()) stack.push_back(n.index), stack.push_back(n.index + 1);
        }
        return sum;
    };
    // Node visits allowed in all: a triangle overlapping most boxes (e.g. many coincident
    // triangles) makes the walks quadratic; then EPO is not computed.
    const uint64_t budget = uint64_t(kEpoVisitsPerTriangle) * leafTriangles.size() + 100'000;
    std::atomic<uint64_t> visited{0};
    std::atomic<bool> overBudget{false};
    const auto run = [&] {
        // Fixed chunks summed in a fixed tree: the same rounding whatever the thread count.
        return tbb::parallel_deterministic_reduce(
            tbb::blocked_range<uint32_t>(0, uint32_t(leafTriangles.size()), 1024), Sums{},
            [&](const tbb::blocked_range<uint32_t>& r, Sums s) {
                std::vector<uint32_t> stack;
                stack.reserve(2 * kBvhMaxDepth);
                uint64_t visits = 0;
                for (uint32_t i = r.begin(); i < r.end() && !overBudget.load(std::memory_order_relaxed); ++i) {
                    s.overlap += overlapOf(i, stack, visits);
                    s.area += triangleArea(leafTriangles[i]);
                }
                if (visited.fetch_add(visits, std::memory_order_relaxed) + visits > budget)
                    overBudget.store(true, std::memory_order_relaxed);
                return s;
            },
            [](Sums a, const Sums& b) {
                a.overlap += b.overlap, a.area += b.area;
                return a;
            },
            tbb::simple_partitioner());
    };
    tbb::task_arena arena(threads == 0 ? tbb::task_arena::automatic : threads);
    const Sums s = arena.execute(run);
    if (overBudget) return std::nullopt;
    return s.area > 0.0 ? s.overlap / s.area : 0.0;
}

}  // namespace bvhlab
