// What an accelerator builds over, apart from the scene that holds it.
#pragma once

#include "framework/core/triangle.h"

#include <cstdint>
#include <span>

namespace bvhlab {

// The triangles an accelerator builds over: all of them by primitive index, and the
// primitive indices of the non-degenerate ones (builders never see the others).
struct PrimitiveSet {
    std::span<const Triangle> triangles;
    std::span<const uint32_t> valid;
};

}  // namespace bvhlab
