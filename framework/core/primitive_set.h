// What an accelerator builds over, apart from the scene that holds it.
#pragma once

#include "framework/core/quadric_shape.h"
#include "framework/core/triangle.h"

#include <algorithm>
#include <cstdint>
#include <span>

namespace bvhlab {

enum class PrimitiveKind : uint8_t { Triangle, Sphere, Cone };

// The primitives an accelerator builds over. One index space: triangle i is primitive i,
// then the spheres, then the cones (sphere j is primitive triangles.size() + j). `valid`
// holds the primitive indices of the non-degenerate ones in ascending order, so the valid
// triangles come first; builders never see the others.
struct PrimitiveSet {
    std::span<const Triangle> triangles;
    std::span<const uint32_t> valid;
    std::span<const Sphere> spheres = {};
    std::span<const Cone> cones = {};

    uint32_t sphereBase() const { return uint32_t(triangles.size()); }
    uint32_t coneBase() const { return uint32_t(triangles.size() + spheres.size()); }
    bool hasQuadrics() const { return !spheres.empty() || !cones.empty(); }

    PrimitiveKind kind(uint32_t prim) const {
        return prim < sphereBase() ? PrimitiveKind::Triangle
                                   : (prim < coneBase() ? PrimitiveKind::Sphere : PrimitiveKind::Cone);
    }
    // Primitive `prim`, which must be a sphere or a cone.
    QuadricShape quadric(uint32_t prim) const {
        if (prim < coneBase()) return spheres[prim - sphereBase()];
        return cones[prim - coneBase()];
    }

    // The valid triangles' indices (a prefix of `valid`) and the valid quadrics' (the rest).
    std::span<const uint32_t> validTriangles() const { return valid.first(quadricStart()); }
    std::span<const uint32_t> validQuadrics() const { return valid.subspan(quadricStart()); }

private:
    size_t quadricStart() const {
        if (!hasQuadrics()) return valid.size();
        return size_t(std::lower_bound(valid.begin(), valid.end(), sphereBase()) - valid.begin());
    }
};

}  // namespace bvhlab
