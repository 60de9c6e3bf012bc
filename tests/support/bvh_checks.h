// Test-side checks of a binary BVH shared by the BVH tests: random triangle soups, the walk
// that checks every structural invariant of the pair layout, and both queries against brute
// force on random rays.
#pragma once

#include "accel/bvh/builder_table.h"
#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/layout/binary_bvh.h"
#include "tests/support/triangle_soup.h"

#include <cstdint>
#include <vector>

namespace bvhlab::test {

// Triangles with corners in [0, extent)^3 and edge lengths up to `size`.
Soup randomSoup(size_t n, uint32_t seed, float extent = 10.0f, float size = 1.0f);

// Triangles of sizes from 1e-6 to 1e3 (log-uniform), positions over a 1e3 cube.
Soup mixedScaleSoup(size_t n, uint32_t seed);

// The unit right triangle at the origin and a copy moved by `shift`: the smallest two-leaf tree.
Soup triangleAndCopy(Vec3 shift);

// The builders of the table that build with the shared recursion or as ploc (sbvh: builders/test_sbvh.cpp).
std::vector<BuilderRecord> allBuilders();

// Unit squares (two triangles each) facing each axis on the lattice planes 0..planes, over
// [0, cells)^2 of the other two axes: rays along an axis start on node box planes and graze
// the squares' edges.
void addLatticeSquares(Soup& soup, int planes, int cells);

// Rays along each axis, both ways, through addLatticeSquares(soup, planes, planes): on lattice
// lines (0, 1, planes) and between them (0.5, 0.25, 2), starting outside the lattice.
std::vector<Ray> axisRaysThroughLattice(int planes);

struct TreeFacts {
    size_t nodes = 0, leaves = 0, maxLeaf = 0;
    int maxDepth = 0;
};

// Checks every structural invariant and returns the counts found by walking the tree:
// each valid primitive exactly once in the leaves, leaf ranges tiling the leaf arrays, the
// leaf triangles the primitives' own, boxes exactly the union of what they hold (children
// inside their parent, triangles inside their leaf), sibling pairs at even indices.
TreeFacts checkTree(const BinaryBvh& bvh, const Soup& soup);

// Builds, checks the tree and that BuildStats reports what the walk found.
TreeFacts buildAndCheck(BvhAccelerator<BinaryBvh>& accel, const Soup& soup);

// The reported SAH (fillTreeStats) with C_trav = C_isect = 1.
double sahOf(const BinaryBvh& bvh);

// Both queries against brute force on `count` rays.
void expectAgreesWithNaive(const Accelerator& accel, const Soup& soup, int count, float extent, uint32_t seed);

}  // namespace bvhlab::test
