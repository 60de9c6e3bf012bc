// Small scenes the Embree tests share: one whose degenerate primitives Embree never sees, a ray
// along z, and a closed scene of a few hundred triangles.
#pragma once

#include <bvhlab/triangle.h>
#include "framework/core/accelerator.h"
#include "framework/scene/procedural.h"
#include "framework/scene/scene.h"

#include <vector>

namespace bvhlab::test {

// A unit right triangle in the plane z = `z`: v0 = (0,0,z), v1 = (1,0,z), v2 = (0,1,z).
inline Triangle flatTriangle(float z) { return {{0, 0, z}, {1, 0, z}, {0, 1, z}}; }

// Primitives 0 and 2 are degenerate (a point, and a line) and not in `valid`; 1 lies at z = 2,
// 3 at z = 5. Embree sees two triangles; its primIDs 0, 1 must come back as 1, 3.
struct SkippingScene {
    std::vector<Triangle> triangles{
        {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}},
        flatTriangle(2.0f),
        {{0, 0, 3}, {1, 0, 3}, {2, 0, 3}},
        flatTriangle(5.0f),
    };
    std::vector<uint32_t> valid{1, 3};
    PrimitiveSet prims() const { return {triangles, valid}; }
};

inline Ray rayAlongZ(float x, float y, float tmin = 0.0f, float tmax = kInfinity) {
    Ray ray;
    ray.org = {x, y, 0.0f};
    ray.dir = {0.0f, 0.0f, 1.0f};
    ray.tmin = tmin;
    ray.tmax = tmax;
    return ray;
}

// An icosphere, a slab under it and a torus above.
inline Scene smallScene() {
    Scene scene;
    addIcosphere(scene, Vec3(0.0f), 1.0f, 2, 0);
    addBox(scene, Vec3(-2.0f, -2.0f, -2.0f), Vec3(2.0f, -1.5f, 2.0f), 0);
    addTorus(scene, Vec3(0.0f, 1.5f, 0.0f), 1.0f, 0.25f, 16, 8, 0);
    scene.finalize();
    return scene;
}

}  // namespace bvhlab::test
