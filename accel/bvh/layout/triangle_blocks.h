// The leaves of the wide layouts: their triangles in blocks of eight, stored lane by lane (SoA,
// as Embree's triangle4v, but at AVX's width), so that one SIMD test
// (traverse/triangle_block_test.h) checks eight triangles of a leaf at once. Eight, not four:
// a block costs one test either way, and the SAH then charges leaves by eights, which halves
// the leaves and the build time (docs/performance.md, "Studies"). A leaf of n triangles takes
// ceil(n / 8) blocks of its own; the lanes past its last triangle repeat that triangle, with
// kInvalidPrimitive as their primitive. A repeat hits exactly where the triangle does, in a
// later lane, and the lowest lane wins a tie: the traversal tests whole blocks without a lane
// mask and never reports a repeat.
#pragma once

#include <bvhlab/triangle.h>
#include "accel/bvh/layout/traversal_allocator.h"

#include <cstdint>
#include <vector>

namespace bvhlab {

struct alignas(32) TriangleBlock {
    static constexpr int kLanes = 8;
    float vertex[3][3][kLanes];  // [vertex 0-2][axis x-z][lane]

    Triangle triangle(int lane) const {
        const auto v = [&](int k) { return Vec3(vertex[k][0][lane], vertex[k][1][lane], vertex[k][2][lane]); };
        return {v(0), v(1), v(2)};
    }
    void set(int lane, const Triangle& tri) {
        const Vec3* v[3] = {&tri.v0, &tri.v1, &tri.v2};
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) vertex[k][a][lane] = (*v[k])[a];
    }
};
static_assert(sizeof(TriangleBlock) == 288);

inline constexpr uint32_t blocksFor(uint32_t triangles) {
    return (triangles + TriangleBlock::kLanes - 1) / TriangleBlock::kLanes;
}

// A leaf of these arrays names its first block and its triangle count; the triangle in lane l
// of block b is at position kLanes * b + l of primIndices.
struct TriangleBlockLeaves {
    // The primitive index of each lane, reported in Hit::primitive (kInvalidPrimitive: padding).
    std::vector<uint32_t> primIndices;
    std::vector<TriangleBlock, TraversalAllocator<TriangleBlock>> blocks;

    // Sizes the arrays for `blocks` blocks, to be filled by writeLeaf.
    void resizeLeaves(uint32_t blocks) {
        this->blocks.resize(blocks);
        primIndices.resize(size_t(blocks) * TriangleBlock::kLanes);
    }

    // Writes a leaf of `count` triangles (primitive indices `prims`) into the blocks from
    // `first` on, which must exist (resizeLeaves); padding lanes included.
    void writeLeaf(uint32_t first, const Triangle* triangles, const uint32_t* prims, uint32_t count) {
        for (uint32_t i = 0, end = blocksFor(count) * TriangleBlock::kLanes; i < end; ++i) {
            const bool real = i < count;
            blocks[first + i / TriangleBlock::kLanes].set(int(i % TriangleBlock::kLanes),
                                                          triangles[real ? i : count - 1]);
            primIndices[size_t(first) * TriangleBlock::kLanes + i] = real ? prims[i] : kInvalidPrimitive;
        }
    }

    // The triangles of the leaf of `count` blocks from `first` on: its padding left out.
    uint32_t trianglesIn(uint32_t first, uint32_t count) const {
        const uint32_t* last = &primIndices[size_t(first + count - 1) * TriangleBlock::kLanes];
        uint32_t triangles = (count - 1) * TriangleBlock::kLanes;
        for (int l = 0; l < TriangleBlock::kLanes; ++l) triangles += last[l] != kInvalidPrimitive ? 1 : 0;
        return triangles;
    }

    // Appends a leaf of `count` triangles; returns its first block.
    uint32_t appendLeaf(const Triangle* triangles, const uint32_t* prims, uint32_t count) {
        const uint32_t first = uint32_t(blocks.size());
        resizeLeaves(first + blocksFor(count));
        writeLeaf(first, triangles, prims, count);
        return first;
    }

    size_t leafBytes() const { return primIndices.size() * sizeof(uint32_t) + blocks.size() * sizeof(TriangleBlock); }
};

}  // namespace bvhlab
