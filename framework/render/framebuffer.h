// The render's per-pixel outputs: colour and the arbitrary output values a BVH
// researcher inspects (depth, primitive, normal, and the per-pixel query cost).
#pragma once

#include <bvhlab/math.h>

#include <vector>

namespace bvhlab {

struct Framebuffer {
    int width = 0, height = 0;
    std::vector<Vec3> color;
    std::vector<float> depth;              // distance to the first hit of the first sample; +inf on a miss
    std::vector<uint32_t> primitive;       // primitive of that hit; kInvalidPrimitive on a miss
    std::vector<Vec3> normal;              // its shading normal; 0 on a miss
    std::vector<float> traversalSteps;     // N_TR of every query of the pixel, all samples
    std::vector<float> intersectionTests;  // N_IT likewise

    // Throws InputError, with the size it needs, when it would not fit in the memory available
    // (framework/core/available_memory.h) with room to write its images.
    Framebuffer(int w, int h);
    // What a w x h framebuffer allocates.
    static size_t bytesFor(int w, int h);
    size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
};

}  // namespace bvhlab
