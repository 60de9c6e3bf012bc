#include "accel/verify/closed_meshes.h"

#include "framework/scene/procedural.h"

#include <fmt/format.h>

#include <map>
#include <tuple>

namespace bvhlab::verify {
namespace {

void addIndexedTriangle(Scene& scene, uint32_t a, uint32_t b, uint32_t c, uint32_t material) {
    scene.indices.emplace_back(a, b, c);
    if (!scene.materialIds.empty() || material != 0) {
        scene.materialIds.resize(scene.indices.size() - 1, 0);
        scene.materialIds.push_back(material);
    }
}

}  // namespace

void addSubdividedBox(Scene& scene, const Vec3& lower, const Vec3& upper, int n, uint32_t material) {
    // Grid coordinate idx (0..n) along axis a: the same float wherever it is used.
    auto coordinate = [&](int a, int idx) {
        if (idx == 0) return lower[a];
        if (idx == n) return upper[a];
        return float(double(lower[a]) + (double(upper[a]) - double(lower[a])) * double(idx) / double(n));
    };
    std::map<std::tuple<int, int, int>, uint32_t> ids;
    auto vertex = [&](int ix, int iy, int iz) {
        const auto [it, inserted] = ids.try_emplace({ix, iy, iz}, uint32_t(scene.positions.size()));
        if (inserted) scene.positions.emplace_back(coordinate(0, ix), coordinate(1, iy), coordinate(2, iz));
        return it->second;
    };
    for (int k = 0; k < 3; ++k)
        for (int side = 0; side < 2; ++side) {
            const int u = (k + 1) % 3, v = (k + 2) % 3;  // e_u x e_v = e_k
            auto at = [&](int i, int j) {
                int idx[3];
                idx[k] = side * n;
                idx[u] = i;
                idx[v] = j;
                return vertex(idx[0], idx[1], idx[2]);
            };
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    const uint32_t p00 = at(i, j), p10 = at(i + 1, j), p11 = at(i + 1, j + 1), p01 = at(i, j + 1);
                    if (side == 1) {  // normal +e_k: counter-clockwise in (u, v)
                        addIndexedTriangle(scene, p00, p10, p11, material);
                        addIndexedTriangle(scene, p00, p11, p01, material);
                    } else {
                        addIndexedTriangle(scene, p00, p11, p10, material);
                        addIndexedTriangle(scene, p00, p01, p11, material);
                    }
                }
        }
}

Scene makeIcosphereMesh(int subdivisions) {
    Scene scene;
    scene.name = fmt::format("icosphere{}", subdivisions);
    addIcosphere(scene, Vec3(0.3f, -0.2f, 0.1f), 1.7f, subdivisions, 0);
    scene.finalize();
    return scene;
}

Scene makeSubdividedCubeMesh(int n) {
    Scene scene;
    scene.name = fmt::format("cube{}", n);
    addSubdividedBox(scene, Vec3(-1.1f, -0.6f, 0.25f), Vec3(0.9f, 1.3f, 2.05f), n, 0);
    scene.finalize();
    return scene;
}

Scene makeTorusMesh(int majorSegments, int minorSegments) {
    Scene scene;
    scene.name = fmt::format("torus{}x{}", majorSegments, minorSegments);
    addTorus(scene, Vec3(1.0f, 2.0f, -1.0f), 2.0f, 0.6f, majorSegments, minorSegments, 0);
    scene.finalize();
    return scene;
}

Scene makeClosedTrioScene(int icosphereSubdivisions, int cubeN, int torusMajor, int torusMinor) {
    Scene scene;
    scene.name =
        fmt::format("trio(icosphere{},cube{},torus{}x{})", icosphereSubdivisions, cubeN, torusMajor, torusMinor);
    addIcosphere(scene, Vec3(-4.0f, 0.1f, 0.0f), 1.2f, icosphereSubdivisions, 0);
    addSubdividedBox(scene, Vec3(-1.2f, -1.0f, -1.0f), Vec3(1.1f, 1.0f, 1.25f), cubeN, 0);
    addTorus(scene, Vec3(4.5f, 0.0f, 0.3f), 1.5f, 0.5f, torusMajor, torusMinor, 0);
    scene.finalize();
    return scene;
}
std::vector<std::function<Scene()>> closedMeshFamily(const std::string& family) {
    if (family == "icosphere") return {[] { return makeIcosphereMesh(2); }, [] { return makeIcosphereMesh(6); }};
    if (family == "cube") return {[] { return makeSubdividedCubeMesh(4); }, [] { return makeSubdividedCubeMesh(64); }};
    if (family == "torus") return {[] { return makeTorusMesh(24, 12); }, [] { return makeTorusMesh(384, 96); }};
    return {};
}

}  // namespace bvhlab::verify
