// The scene model every reader fills and every accelerator builds over: triangle meshes in
// one flat list, NFF's spheres and cones, materials, point lights and an optional camera.
#pragma once

#include <bvhlab/triangle.h>
#include <glm/glm.hpp>

#include <bvhlab/primitive_set.h>

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace bvhlab {

struct Material {
    Vec3 diffuse{0.8f};
    float mirror = 0.0f;        // reflectance of a perfect mirror, used when depthLimit > 1 (NFF Ks)
    float shine = 0.0f;         // Phong exponent of the highlight (NFF Shine)
    float transmission = 0.0f;  // transmittance of a refracting surface (NFF T)
    float ior = 1.0f;           // its index of refraction
};

struct PointLight {
    Vec3 position{0.0f};
    // Irradiance the light gives at the centre of the scene's bounds (NFF's convention of 1 =
    // full light, made scale-free); the renderer lets it fall off with the squared distance.
    Vec3 intensity{1.0f};
};

// The largest image width or height (Camera::width and Camera::height have the same range).
inline constexpr int kMaxImageSide = 16384;

struct CameraSpec {
    Vec3 from{0.0f, 0.0f, 1.0f};
    Vec3 at{0.0f};
    Vec3 up{0.0f, 1.0f, 0.0f};
    float fovyDegrees = 45.0f;
    int width = 512;
    int height = 512;
};

// What loading kept but will not build over, reported after loading.
struct LoadReport {
    size_t degenerateTriangles = 0;  // see isDegenerate (scene.h, sphere.h, cone.h): kept,
    size_t degenerateSpheres = 0;    // never built over
    size_t degenerateCones = 0;
    size_t skippedPolygons = 0;           // faces of 4+ vertices without an exact cover (PolygonProblem)
    size_t earClippedPolygons = 0;        // non-convex faces, triangulated by ear clipping
    size_t skippedTextureReferences = 0;  // AFF's textures (tt, ttp, texturecoords): geometry read, image not
    std::vector<std::string> warnings;
};

struct Scene {
    std::string name;
    std::filesystem::path source;  // empty for generated scenes

    // Meshes as read, one flat list. Triangle i (the primitive index) is indices[i]:
    // its place in file order after triangulation (appendPolygon), degenerate triangles
    // included.
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;  // per vertex; empty when the file has none
    std::vector<glm::uvec3> indices;
    std::vector<uint32_t> materialIds;  // per triangle; empty means material 0 everywhere
    // NFF's native quadrics, each with its material: primitives triangleCount() + j (spheres)
    // and triangleCount() + spheres.size() + k (cones), PrimitiveSet's index space.
    std::vector<Sphere> spheres;
    std::vector<uint32_t> sphereMaterialIds;
    std::vector<Cone> cones;
    std::vector<uint32_t> coneMaterialIds;
    std::vector<Material> materials = std::vector<Material>(1);  // (not {Material{}}: GCC 12 warns on it)

    std::optional<CameraSpec> camera;
    std::vector<PointLight> lights;
    std::optional<Vec3> background;
    LoadReport report;

    // Derived by finalize().
    std::vector<Triangle> triangles;
    std::vector<uint32_t> validPrimitives;  // of every kind, ascending (PrimitiveSet::valid)
    Bounds3 bounds;                         // of the valid primitives

    // Builds the derived arrays and counts degenerate primitives; readers call it last.
    void finalize();
    PrimitiveSet primitives() const { return {triangles, validPrimitives, spheres, cones}; }
    uint32_t materialOf(uint32_t prim) const {
        if (prim < triangleCount()) return materialIds.empty() ? 0 : materialIds[prim];
        if (prim < triangleCount() + spheres.size()) return sphereMaterialIds[prim - triangleCount()];
        return coneMaterialIds[prim - triangleCount() - spheres.size()];
    }
    size_t triangleCount() const { return indices.size(); }
    size_t primitiveCount() const { return indices.size() + spheres.size() + cones.size(); }
};

// Zero area, a NaN or infinite vertex, or a normal that cannot be normalised in float (its
// squared length under- or overflows): no hit on it could be shaded or offset.
bool isDegenerate(const Triangle& tri);

}  // namespace bvhlab
