#include "framework/scene/scene.h"

#include <cmath>

namespace bvhlab {

bool isDegenerate(const Triangle& tri) {
    if (!isFinite(tri.v0) || !isFinite(tri.v1) || !isFinite(tri.v2)) return true;
    // The renderer shades and offsets rays with this very normal. A finite cross product can
    // still fail to normalise: legs of 1e-20 give a denormal 1e-40 whose square is 0 (NaN);
    // legs beyond about 4e9, a square that overflows (a zero normal).
    const Vec3 n = glm::normalize(tri.geometricNormal());
    return !isFinite(n) || std::abs(glm::length(n) - 1.0f) > 1e-3f;
}

void Scene::finalize() {
    triangles.resize(indices.size());
    validPrimitives.clear();
    validPrimitives.reserve(indices.size() + spheres.size() + cones.size());
    bounds = Bounds3();
    for (size_t i = 0; i < indices.size(); ++i) {
        const glm::uvec3 idx = indices[i];
        triangles[i] = {positions[idx.x], positions[idx.y], positions[idx.z]};
        if (isDegenerate(triangles[i])) continue;
        validPrimitives.push_back(uint32_t(i));
        bounds.extend(triangles[i].bounds());
    }
    report.degenerateTriangles = indices.size() - validPrimitives.size();
    // The quadrics follow the triangles in the index space (PrimitiveSet); a scene built in
    // code may leave their materials out (material 0).
    sphereMaterialIds.resize(spheres.size(), 0);
    coneMaterialIds.resize(cones.size(), 0);
    uint32_t prim = uint32_t(indices.size());
    const auto addQuadrics = [&](const auto& shapes, size_t& degenerate) {
        degenerate = 0;
        for (const auto& shape : shapes) {
            if (isDegenerate(shape)) {
                ++degenerate;
            } else {
                validPrimitives.push_back(prim);
                bounds.extend(shape.bounds());
            }
            ++prim;
        }
    };
    addQuadrics(spheres, report.degenerateSpheres);
    addQuadrics(cones, report.degenerateCones);
    if (materials.empty()) materials.push_back(Material{});
}

}  // namespace bvhlab
