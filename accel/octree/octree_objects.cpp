#include "accel/octree/octree_objects.h"

#include <cmath>

namespace bvhlab::octree {

bool continuesFan(const Triangle& previous, const Triangle& next) {
    if (!(next.v0 == previous.v0 && next.v1 == previous.v2)) return false;
    const DVec3 a = math::cross(DVec3(previous.v1) - DVec3(previous.v0), DVec3(previous.v2) - DVec3(previous.v0));
    const DVec3 b = math::cross(DVec3(next.v1) - DVec3(next.v0), DVec3(next.v2) - DVec3(next.v0));
    // One plane, within the loader's tolerance for a polygon's corners (1e-3 of its size).
    return math::dot(a, b) > 0.0 && math::length(math::cross(a, b)) <= 1e-3 * math::length(a) * math::length(b);
}

OctreeObjects octreeObjects(const PrimitiveSet& prims, bool polygons) {
    OctreeObjects objects;
    const View<const uint32_t> valid = prims.valid;
    for (size_t i = 0; i < valid.size(); ++i) {
        const uint32_t p = valid[i];
        const bool triangle = prims.kind(p) == PrimitiveKind::Triangle;
        const Bounds3 box = triangle ? prims.triangles[p].bounds() : boundsOf(prims.quadric(p));
        if (polygons && triangle && i > 0 && valid[i - 1] + 1 == p && prims.kind(p - 1) == PrimitiveKind::Triangle &&
            continuesFan(prims.triangles[p - 1], prims.triangles[p])) {
            objects.boxes.back().extend(box);
            continue;
        }
        objects.first.push_back(uint32_t(i));
        objects.boxes.push_back(box);
    }
    objects.first.push_back(uint32_t(valid.size()));
    return objects;
}

}  // namespace bvhlab::octree
