// Havran's recursive traversal TA_B^rec (his thesis, 2000) with an explicit stack: at each inner
// node the ray's interval [t0, t1] is cut at the plane, the near child taken first and the far one
// pushed with its own interval; a popped child that starts beyond the closest hit so far is
// skipped. In double, and with a positional margin (kRayMargin): each child is entered where the
// ray comes within the margin of its side of the plane, so a hit on or next to a split plane,
// wherever the watertight test's rounding puts it, is in a leaf the ray visits.
#pragma once

#include "accel/kdtree/kdtree_builder.h"

#include <bvhlab/counters.h>
#include <bvhlab/ray.h>

#include <algorithm>
#include <cmath>

namespace bvhlab::kdtree {

// Calls visit(leaf) for each leaf the ray's interval passes through, near to far, while it returns
// false; `tmax` (the closest hit so far, which visit may lower) prunes the leaves beyond it.
// Counts every node visited in N_TR. Rays with an origin or direction that is not finite are not
// walked (the caller tests them otherwise).
template <typename Visit>
void walkLeaves(const KdTree& tree, const Ray& ray, const float& tmax, QueryCounters& counters, Visit&& visit) {
    if (tree.nodes.empty()) return;
    const DVec3 org(ray.org), dir(ray.dir);
    const Bounds3& box = tree.bounds;
    const Vec3 sceneMagnitude = math::max(math::abs(box.lower), math::abs(box.upper));
    const DVec3 orgMagnitude = math::abs(org);
    const double margin =
        kRayMargin * std::max({double(sceneMagnitude.x), double(sceneMagnitude.y), double(sceneMagnitude.z),
                               orgMagnitude.x, orgMagnitude.y, orgMagnitude.z});
    const double dirMagnitude = std::max({std::abs(dir.x), std::abs(dir.y), std::abs(dir.z)});
    // The ray's interval, widened by the margin, clipped to the root's box widened alike.
    double t0 = double(ray.tmin) - margin / dirMagnitude, t1 = double(ray.tmax) + margin / dirMagnitude;
    DVec3 inv, marginT;  // marginT: the t the ray takes to cross the margin along each axis
    for (int a = 0; a < 3; ++a) {
        const double lo = double(box.lower[a]) - margin, hi = double(box.upper[a]) + margin;
        if (dir[a] == 0.0) {
            if (org[a] < lo || org[a] > hi) return;
            inv[a] = marginT[a] = 0.0;
            continue;
        }
        inv[a] = 1.0 / dir[a];
        marginT[a] = margin * std::abs(inv[a]);
        const double ta = (lo - org[a]) * inv[a], tb = (hi - org[a]) * inv[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
    }
    if (!(t0 <= t1)) return;

    struct Pending {
        uint32_t node;
        double t0, t1;
    };
    Pending stack[65];  // one far child per level: the depth is at most 64
    int pending = 0;
    uint32_t index = 0;
    for (;;) {
        const KdNode* node = &tree.nodes[index];
        ++counters.traversalSteps;
        while (!node->isLeaf()) {
            const int k = node->axis();
            const double split = node->split();
            const uint32_t below = index + 1, above = node->aboveChild();
            uint32_t near, far;
            double nearEnd, farStart;  // the ray is within the margin of the near side for t <= nearEnd
            if (dir[k] == 0.0) {
                const bool inBelow = org[k] <= split + margin, inAbove = org[k] >= split - margin;
                near = inBelow ? below : above;
                far = inBelow ? above : below;
                nearEnd = t1;
                farStart = inBelow && inAbove ? t0 : kInfinity;
            } else {
                const double tPlane = (split - org[k]) * inv[k];
                const bool belowFirst = dir[k] > 0.0;
                near = belowFirst ? below : above;
                far = belowFirst ? above : below;
                nearEnd = tPlane + marginT[k];
                farStart = tPlane - marginT[k];
            }
            if (nearEnd < t0) {
                index = far;
            } else if (farStart > t1) {
                index = near;
            } else {
                stack[pending++] = {far, std::max(t0, farStart), t1};
                index = near;
                t1 = std::min(t1, nearEnd);
            }
            node = &tree.nodes[index];
            ++counters.traversalSteps;
        }
        if (visit(*node)) return;
        do {
            if (pending == 0) return;
            const Pending& p = stack[--pending];
            index = p.node, t0 = p.t0, t1 = p.t1;
        } while (t0 > double(tmax));
    }
}

}  // namespace bvhlab::kdtree
