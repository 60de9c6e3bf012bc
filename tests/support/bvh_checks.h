// Test-side checks of a binary BVH shared by the BVH tests: random triangle soups, the walk
// that checks every structural invariant of the pair layout, and both queries against brute
// force on random rays.
#pragma once

#include "accel/bvh/layout/binary_bvh.h"
#include "tests/support/triangle_soup.h"

#include <cstdint>

namespace bvhlab::test {

// Triangles with corners in [0, extent)^3 and edge lengths up to `size`.
Soup randomSoup(size_t n, uint32_t seed, float extent = 10.0f, float size = 1.0f);

// Unit squares (two triangles each) facing each axis on the lattice planes 0..planes, over
// [0, cells)^2 of the other two axes: rays along an axis start on node box planes and graze
// the squares' edges.
void addLatticeSquares(Soup& soup, int planes, int cells);

struct TreeFacts {
    size_t nodes = 0, leaves = 0, maxLeaf = 0;
    int maxDepth = 0;
};

// Checks every structural invariant and returns the counts found by walking the tree:
// each valid primitive exactly once in the leaves, leaf ranges tiling the leaf arrays, the
// leaf triangles the primitives' own, boxes exactly the union of what they hold (children
// inside their parent, triangles inside their leaf), sibling pairs at even indices.
TreeFacts checkTree(const BinaryBvh& bvh, const Soup& soup);

// The reported SAH (fillTreeStats) with C_trav = C_isect = 1.
double sahOf(const BinaryBvh& bvh);

// Both queries against brute force on `count` rays.
void expectAgreesWithNaive(const Accelerator& accel, const Soup& soup, int count, float extent, uint32_t seed);

}  // namespace bvhlab::test
