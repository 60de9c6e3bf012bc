// What an accelerator builds over, apart from the scene that holds it.
#pragma once

#include <bvhlab/quadric_shape.h>
#include <bvhlab/triangle.h>
#include <bvhlab/view.h>

#include <cstdint>

namespace bvhlab {

enum class PrimitiveKind : uint8_t { Triangle, Sphere, Cone };

// The primitives an accelerator builds over. One index space: triangle i is primitive i,
// then the spheres, then the cones (sphere j is primitive triangles.size() + j). `valid`
// holds the primitive indices of the non-degenerate ones in ascending order, so the valid
// triangles come first; builders never see the others.
struct PrimitiveSet {
    View<const Triangle> triangles;
    View<const uint32_t> valid;
    View<const Sphere> spheres = {};
    View<const Cone> cones = {};

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
    View<const uint32_t> validTriangles() const { return valid.first(quadricStart()); }
    View<const uint32_t> validQuadrics() const { return valid.subspan(quadricStart()); }

private:
    size_t quadricStart() const {
        if (!hasQuadrics()) return valid.size();
        // The first valid index >= sphereBase(), by bisection (std::lower_bound).
        size_t begin = 0, end = valid.size();
        while (begin < end) {
            const size_t middle = begin + (end - begin) / 2;
            if (valid[middle] < sphereBase())
                begin = middle + 1;
            else
                end = middle;
        }
        return begin;
    }
};

}  // namespace bvhlab
