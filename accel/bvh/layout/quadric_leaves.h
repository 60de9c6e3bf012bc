// The leaves of the tree over a scene's spheres and cones. Triangles and quadrics get a tree
// each (as Embree builds one BVH per geometry type and traverses them in turn): the triangle
// layouts and their SIMD leaves stay as they are, and a scene without quadrics pays one test
// of an empty tree per query. The quadric tree is binary, built by the same builder over the
// quadrics' boxes; its leaves hold copies of the shapes in leaf order.
#pragma once

#include <bvhlab/quadric_shape.h>
#include "accel/bvh/layout/bvh_node.h"
#include "accel/bvh/layout/leaf_arrays.h"

#include <cstdint>
#include <vector>

namespace bvhlab {

struct QuadricLeaves {
    std::vector<uint32_t> primIndices;  // the primitive index of each shape, reported in Hit
    std::vector<QuadricShape> leafShapes;

    size_t leafBytes() const {
        return primIndices.size() * sizeof(uint32_t) + leafShapes.size() * sizeof(QuadricShape);
    }
};

// Laid out as BinaryBvh (root at 0, a padding slot, sibling pairs); leaf l holds
// leafShapes[l.index .. l.index + l.count).
using QuadricBvh = NodeTree<BvhNode, QuadricLeaves>;

}  // namespace bvhlab
