// The two traversals of Havran's octree comparison that bvhlab has, in double precision, each
// calling visit(leaf, tExit) for the leaves a ray's interval crosses, in the order it crosses
// them, while visit returns true; tExit is the t at which the ray leaves the leaf (tmax in the
// last one). Each counts the nodes it visits into `steps` (Havran's N_TS). No mailboxes.
// - Octree84 (Glassner 1984): from the point where the ray enters the root, locate the leaf
//   holding the point by descending from the root; test it; move the point to where the ray
//   leaves the leaf, and locate again. A point on a plane goes to the side the ray is heading
//   (the faces it leaves through are set exactly), so every located leaf lies further along the
//   ray. N_TS counts every node of every descent.
// - Octree93 (Gargantini and Atkinson 1993): recursive and top down; in an inner node the
//   parameters t of the three planes order its children along the ray, and the children the ray
//   crosses are visited in that order. N_TS counts every node visited, inner or leaf.
// A ray lying in a plane goes to the side below it, which refers to every object touching the
// plane (closed boxes: octree_nodes.h).
#pragma once

#include "accel/octree/octree_nodes.h"

#include <bvhlab/ray.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>

namespace bvhlab::octree {

enum class Traversal { Octree84, Octree93 };
std::optional<Traversal> parseTraversal(std::string_view name);

// The ray in double precision, clipped to the root's box: [t0, t1], empty when it misses it.
struct ClippedRay {
    DVec3 org, dir, inv;
    double t0 = 0.0, t1 = 0.0;
    bool inside = false;
    ClippedRay(const Octree& tree, const Ray& ray) : org(ray.org), dir(ray.dir) {
        inside = clipToBox(ray, tree.lower, tree.upper, t0, t1);
        for (int a = 0; a < 3; ++a) inv[a] = dir[a] == 0.0 ? 0.0 : 1.0 / dir[a];
    }
    bool hits() const { return inside; }
    // The t at which the ray meets the plane x[axis] = position (infinite when parallel to it).
    double at(int axis, double position) const {
        return dir[axis] == 0.0 ? double(kInfinity) : (position - org[axis]) * inv[axis];
    }
};

template <typename Visit>
void walkOctree84(const Octree& tree, const ClippedRay& r, uint64_t& steps, Visit&& visit) {
    // The point where the ray enters the root, the faces it enters through set exactly.
    double t = r.t0;
    DVec3 p;
    for (int a = 0; a < 3; ++a) {
        p[a] = std::clamp(r.org[a] + t * r.dir[a], tree.lower[a], tree.upper[a]);
        if (r.dir[a] != 0.0 && r.at(a, r.dir[a] > 0.0 ? tree.lower[a] : tree.upper[a]) == t)
            p[a] = r.dir[a] > 0.0 ? tree.lower[a] : tree.upper[a];
    }
    // Every step lies further along the ray; the bound only guards against a non-finite ray.
    for (size_t guard = 0; guard <= tree.nodes.size(); ++guard) {
        DVec3 lo = tree.lower, hi = tree.upper;
        uint32_t n = 0;
        ++steps;
        while (!tree.nodes[n].isLeaf()) {
            const OctreeNode& node = tree.nodes[n];
            uint32_t c = 0;
            for (int a = 0; a < 3; ++a) {
                const bool above = p[a] > node.split[a] || (p[a] == node.split[a] && r.dir[a] > 0.0);
                c |= uint32_t(above) << a;
                (above ? lo : hi)[a] = node.split[a];
            }
            n = node.firstChild + c;
            ++steps;
        }
        double face[3], exit = r.t1;
        for (int a = 0; a < 3; ++a) {
            face[a] = r.dir[a] > 0.0 ? r.at(a, hi[a]) : (r.dir[a] < 0.0 ? r.at(a, lo[a]) : double(kInfinity));
            exit = std::min(exit, face[a]);
        }
        if (!visit(n, exit) || !(exit < r.t1)) return;
        t = std::max(exit, t);
        for (int a = 0; a < 3; ++a)
            p[a] = face[a] <= t ? (r.dir[a] > 0.0 ? hi[a] : lo[a]) : std::clamp(r.org[a] + t * r.dir[a], lo[a], hi[a]);
    }
}

namespace detail {

template <typename Visit>
bool walkOctree93(const Octree& tree, const ClippedRay& r, uint32_t n, double ta, double tb, uint64_t& steps,
                  Visit& visit) {
    ++steps;
    const OctreeNode& node = tree.nodes[n];
    if (node.isLeaf()) return visit(n, tb);
    double plane[3];
    uint32_t c = 0;
    for (int a = 0; a < 3; ++a) {
        plane[a] = r.at(a, node.split[a]);
        // The child's side at ta: a ray heading up is above its plane from the plane's t on.
        const bool above =
            r.dir[a] > 0.0 ? ta >= plane[a] : (r.dir[a] < 0.0 ? ta < plane[a] : r.org[a] > node.split[a]);
        c |= uint32_t(above) << a;
    }
    for (double t = ta;;) {
        double next = tb;
        for (int a = 0; a < 3; ++a)
            if (plane[a] > t && plane[a] < next) next = plane[a];
        if (!walkOctree93(tree, r, node.firstChild + c, t, next, steps, visit)) return false;
        if (!(next < tb)) return true;
        for (int a = 0; a < 3; ++a)
            if (plane[a] == next) c ^= 1u << a;
        t = next;
    }
}

}  // namespace detail

template <typename Visit>
void walkOctree93(const Octree& tree, const ClippedRay& r, uint64_t& steps, Visit&& visit) {
    detail::walkOctree93(tree, r, 0, r.t0, r.t1, steps, visit);
}

}  // namespace bvhlab::octree
