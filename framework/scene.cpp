#include "framework/scene.h"

namespace bvhlab {

bool isDegenerate(const Triangle& tri) {
    if (!isFinite(tri.v0) || !isFinite(tri.v1) || !isFinite(tri.v2)) return true;
    const Vec3 n = tri.geometricNormal();
    return (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) || !isFinite(n);
}

void Scene::finalize() {
    triangles.resize(indices.size());
    validPrimitives.clear();
    validPrimitives.reserve(indices.size());
    bounds = Bounds3();
    for (size_t i = 0; i < indices.size(); ++i) {
        const glm::uvec3 idx = indices[i];
        triangles[i] = {positions[idx.x], positions[idx.y], positions[idx.z]};
        if (isDegenerate(triangles[i])) continue;
        validPrimitives.push_back(uint32_t(i));
        bounds.extend(triangles[i].bounds());
    }
    report.degenerateTriangles = indices.size() - validPrimitives.size();
    if (materials.empty()) materials.push_back(Material{});
}

}  // namespace bvhlab
