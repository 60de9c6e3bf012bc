// The kd-tree's flat node: 8 bytes, in depth-first order, the child below the plane right after
// its parent. An inner node holds its plane (axis and position) and the index of the child above
// it; a leaf holds its range of the reference array.
#pragma once

#include <bit>
#include <cstdint>

namespace bvhlab::kdtree {

inline constexpr uint32_t kLeafTag = 3;                // the low two bits of a leaf; an inner node's are its axis
inline constexpr uint32_t kMaxIndex = (1u << 30) - 1;  // the upper 30 bits: a child index or a count

class KdNode {
public:
    static KdNode inner(int axis, float split, uint32_t aboveChild) {
        return KdNode(std::bit_cast<uint32_t>(split), (aboveChild << 2) | uint32_t(axis));
    }
    static KdNode leaf(uint32_t firstReference, uint32_t references) {
        return KdNode(firstReference, (references << 2) | kLeafTag);
    }

    bool isLeaf() const { return (bits_ & 3u) == kLeafTag; }
    // Inner nodes: the plane and the child above it (the child below is the next node).
    int axis() const { return int(bits_ & 3u); }
    float split() const { return std::bit_cast<float>(word_); }
    uint32_t aboveChild() const { return bits_ >> 2; }
    // Leaves: references[firstReference() ..+ references()).
    uint32_t firstReference() const { return word_; }
    uint32_t references() const { return bits_ >> 2; }

private:
    KdNode(uint32_t word, uint32_t bits) : word_(word), bits_(bits) {}
    uint32_t word_;
    uint32_t bits_;
};
static_assert(sizeof(KdNode) == 8);

}  // namespace bvhlab::kdtree
