// Where in its pixel a camera sample goes. Deterministic: a sample's position depends only on
// the pixel and the sample index, so images do not change with the thread count.
#pragma once

#include <glm/vec2.hpp>

#include <cmath>
#include <cstdint>

namespace bvhlab {

// Hash-based random numbers in [0, 1) (24 bits).
inline float hashToUnit(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return float(x >> 8) * (1.0f / 16777216.0f);
}

// Sample `s` of `count` in a pixel, as an offset in [0, 1)^2 from its corner. One sample: the
// centre. Otherwise stratified over an nx * ny grid of cells, jittered in its cell, when count
// fills such a grid exactly (2, 4, 6, 9, 12, 16, ...); else uniformly jittered over the pixel,
// since a partly filled grid would leave part of the pixel unsampled (a biased estimate).
inline glm::vec2 sampleOffset(uint32_t pixel, int s, int count) {
    if (count == 1) return {0.5f, 0.5f};
    const uint32_t seed = pixel * 9781u + uint32_t(s) * 6271u;
    const float jx = hashToUnit(seed * 2u + 1u), jy = hashToUnit(seed * 2u + 2u);
    const int nx = int(std::ceil(std::sqrt(float(count))));
    const int ny = (count + nx - 1) / nx;
    if (nx * ny != count) return {jx, jy};
    return {(float(s % nx) + jx) / float(nx), (float(s / nx) + jy) / float(ny)};
}

}  // namespace bvhlab
