// Morton codes (Z-order): the bits of three 10-bit grid coordinates interleaved into 30, so that
// sorting by the code puts points that are close in space mostly close in the order (as the
// LBVH builders, Karras 2012; ploc only needs the order to be local within its search radius).
#pragma once

#include <bvhlab/math.h>

#include <algorithm>
#include <cstdint>

namespace bvhlab {

// The 10 bits of x spread to every third bit of the result.
inline uint32_t spreadBits10(uint32_t x) {
    x &= 0x3ff;
    x = (x | x << 16) & 0x30000ff;
    x = (x | x << 8) & 0x300f00f;
    x = (x | x << 4) & 0x30c30c3;
    x = (x | x << 2) & 0x9249249;
    return x;
}

// Maps points of a box to the 2^10 cells per axis of its grid (a flat axis maps to cell 0).
class MortonGrid {
public:
    explicit MortonGrid(const Bounds3& box) : origin_(box.lower) {
        const Vec3 extent = box.diagonal();
        for (int a = 0; a < 3; ++a) scale_[a] = extent[a] > 0.0f ? kCells / extent[a] : 0.0f;
    }
    static constexpr int kBits = 30;

    uint32_t code(const Vec3& p) const {
        uint32_t cell[3];
        for (int a = 0; a < 3; ++a)
            cell[a] = uint32_t(std::clamp((p[a] - origin_[a]) * scale_[a], 0.0f, kCells - 1.0f));
        return spreadBits10(cell[0]) << 2 | spreadBits10(cell[1]) << 1 | spreadBits10(cell[2]);
    }

private:
    static constexpr float kCells = float(1 << 10);
    Vec3 origin_;
    Vec3 scale_;
};

}  // namespace bvhlab
