#include "framework/scene/procedural.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <map>

namespace bvhlab {
namespace {

void addTriangle(Scene& scene, uint32_t a, uint32_t b, uint32_t c, uint32_t material) {
    scene.indices.emplace_back(a, b, c);
    scene.materialIds.push_back(material);
}

// Material ids must cover every triangle once any triangle has a non-zero one.
void padMaterialIds(Scene& scene) { scene.materialIds.resize(scene.indices.size(), 0); }

}  // namespace

void addLooseTriangle(Scene& scene, const Vec3& a, const Vec3& b, const Vec3& c) {
    const uint32_t base = uint32_t(scene.positions.size());
    scene.positions.insert(scene.positions.end(), {a, b, c});
    scene.indices.emplace_back(base, base + 1, base + 2);
    if (!scene.materialIds.empty()) scene.materialIds.push_back(0);
}

void addQuad(Scene& scene, const Vec3& corner, const Vec3& edge1, const Vec3& edge2, uint32_t material) {
    padMaterialIds(scene);
    const uint32_t base = uint32_t(scene.positions.size());
    scene.positions.insert(scene.positions.end(), {corner, corner + edge1, corner + edge1 + edge2, corner + edge2});
    addTriangle(scene, base, base + 1, base + 2, material);
    addTriangle(scene, base, base + 2, base + 3, material);
}

void addBox(Scene& scene, const Vec3& lower, const Vec3& upper, uint32_t material) {
    const Vec3 d = upper - lower;
    const Vec3 x(d.x, 0, 0), y(0, d.y, 0), z(0, 0, d.z);
    // Six faces, each wound counter-clockwise seen from outside.
    addQuad(scene, lower, y, x, material);
    addQuad(scene, lower + z, x, y, material);
    addQuad(scene, lower, z, y, material);
    addQuad(scene, lower + x, y, z, material);
    addQuad(scene, lower, x, z, material);
    addQuad(scene, lower + y, z, x, material);
}

void addIcosphere(Scene& scene, const Vec3& center, float radius, int subdivisions, uint32_t material) {
    padMaterialIds(scene);
    const float t = (1.0f + std::sqrt(5.0f)) * 0.5f;
    std::vector<Vec3> vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                  {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    std::vector<glm::uvec3> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                     {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                     {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                     {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (Vec3& v : vertices) v = glm::normalize(v);
    for (int level = 0; level < subdivisions; ++level) {
        // Shared midpoints keep the mesh closed: each edge is split once.
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto [it, inserted] = midpoints.try_emplace({key.first, key.second}, uint32_t(vertices.size()));
            if (inserted) vertices.push_back(glm::normalize(vertices[a] + vertices[b]));
            return it->second;
        };
        std::vector<glm::uvec3> finer;
        for (const glm::uvec3& f : faces) {
            const uint32_t ab = midpoint(f.x, f.y), bc = midpoint(f.y, f.z), ca = midpoint(f.z, f.x);
            finer.insert(finer.end(), {{f.x, ab, ca}, {f.y, bc, ab}, {f.z, ca, bc}, {ab, bc, ca}});
        }
        faces = std::move(finer);
    }
    const uint32_t base = uint32_t(scene.positions.size());
    for (const Vec3& v : vertices) scene.positions.push_back(center + radius * v);
    for (const glm::uvec3& f : faces) addTriangle(scene, base + f.x, base + f.y, base + f.z, material);
}

void addTorus(Scene& scene, const Vec3& center, float majorRadius, float minorRadius, int majorSegments,
              int minorSegments, uint32_t material) {
    padMaterialIds(scene);
    const uint32_t base = uint32_t(scene.positions.size());
    const float tau = glm::two_pi<float>();
    for (int i = 0; i < majorSegments; ++i) {
        const float phi = tau * float(i) / float(majorSegments);
        for (int j = 0; j < minorSegments; ++j) {
            const float theta = tau * float(j) / float(minorSegments);
            const float r = majorRadius + minorRadius * std::cos(theta);
            scene.positions.push_back(center +
                                      Vec3(r * std::cos(phi), minorRadius * std::sin(theta), r * std::sin(phi)));
        }
    }
    auto index = [&](int i, int j) {
        return base + uint32_t((i % majorSegments) * minorSegments + (j % minorSegments));
    };
    for (int i = 0; i < majorSegments; ++i)
        for (int j = 0; j < minorSegments; ++j) {
            addTriangle(scene, index(i, j), index(i, j + 1), index(i + 1, j + 1), material);
            addTriangle(scene, index(i, j), index(i + 1, j + 1), index(i + 1, j), material);
        }
}

Scene makeDefaultScene() {
    Scene scene;
    scene.name = "default";
    scene.materials = {
        {Vec3(0.75f), 0.0f},               // 0: floor
        {Vec3(0.8f, 0.25f, 0.2f), 0.0f},   // 1: red
        {Vec3(0.25f, 0.45f, 0.8f), 0.0f},  // 2: blue
        {Vec3(0.9f, 0.8f, 0.3f), 0.0f},    // 3: yellow
        {Vec3(0.1f), 0.85f},               // 4: mirror
    };
    addQuad(scene, Vec3(-4, 0, -4), Vec3(0, 0, 8), Vec3(8, 0, 0), 0);
    addBox(scene, Vec3(-2.2f, 0, -1.0f), Vec3(-1.0f, 2.4f, 0.2f), 1);
    addIcosphere(scene, Vec3(0.3f, 0.9f, 0.6f), 0.9f, 4, 2);
    addTorus(scene, Vec3(2.0f, 0.35f, -0.6f), 0.8f, 0.35f, 48, 24, 3);
    addQuad(scene, Vec3(-3.0f, 0.0f, -2.5f), Vec3(6.0f, 0, 0), Vec3(0, 3.0f, 0), 4);
    scene.lights = {{Vec3(3.0f, 6.0f, 4.0f), Vec3(1.0f)}};
    scene.background = Vec3(0.05f, 0.06f, 0.09f);
    scene.camera = CameraSpec{Vec3(1.0f, 3.2f, 7.5f), Vec3(0.0f, 0.8f, 0.0f), Vec3(0, 1, 0), 45.0f, 640, 480};
    scene.finalize();
    return scene;
}

}  // namespace bvhlab
