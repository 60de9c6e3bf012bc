// Havran's objects from bvhlab's primitives. GOLEM tested a polygon as one object; bvhlab's loader
// cuts a convex polygon into the fan of triangles from its first corner, (c0, c1, c2), (c0, c2,
// c3), ..., consecutive primitives. Counting each triangle as an object makes every node a quad
// (two triangles) reaches refer to two objects, so with MO = 1 it is split down to the maximum
// depth: balls' and tree's ground quads multiply Havran's N_IN by up to 16 (docs/spd.md). So a
// fan is one object again: triangles that follow one another, share the first corner and an edge
// in fan order and face the same way in one plane. A mesh's flat fans become objects as well,
// which changes what the figures count, never the answers.
#pragma once

#include <bvhlab/primitive_set.h>

#include <cstdint>
#include <vector>

namespace bvhlab::octree {

// Object o is the primitives valid[first[o]] .. valid[first[o + 1] - 1] (valid: the
// PrimitiveSet's), with its box boxes[o].
struct OctreeObjects {
    std::vector<uint32_t> first;
    std::vector<Bounds3> boxes;
    size_t size() const { return boxes.size(); }
};

// Does triangle `next` continue the fan of `previous` in one plane?
bool continuesFan(const Triangle& previous, const Triangle& next);

// The objects of prims.valid: with `polygons`, each fan of triangles one object, else each
// primitive one.
OctreeObjects octreeObjects(const PrimitiveSet& prims, bool polygons);

}  // namespace bvhlab::octree
