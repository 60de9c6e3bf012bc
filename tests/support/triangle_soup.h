// A triangle soup for the BVH tests: the triangles and the valid list the builders see.
#pragma once

#include <bvhlab/primitive_set.h>

#include <vector>

namespace bvhlab::test {

// `valid` lists every triangle added unless a test edits it.
struct Soup {
    std::vector<Triangle> triangles;
    std::vector<uint32_t> valid;

    void add(const Triangle& t) {
        valid.push_back(uint32_t(triangles.size()));
        triangles.push_back(t);
    }
    PrimitiveSet prims() const { return {triangles, valid}; }
};

}  // namespace bvhlab::test
