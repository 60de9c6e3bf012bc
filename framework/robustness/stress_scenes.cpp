#include "framework/robustness/stress_scenes.h"

#include "framework/scene/procedural.h"

#include <fmt/format.h>

#include <map>
#include <tuple>

namespace bvhlab {
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
    scene.name = fmt::format("trio(icosphere{},cube{},torus{}x{})", icosphereSubdivisions, cubeN, torusMajor, torusMinor);
    addIcosphere(scene, Vec3(-4.0f, 0.1f, 0.0f), 1.2f, icosphereSubdivisions, 0);
    addSubdividedBox(scene, Vec3(-1.2f, -1.0f, -1.0f), Vec3(1.1f, 1.0f, 1.25f), cubeN, 0);
    addTorus(scene, Vec3(4.5f, 0.0f, 0.3f), 1.5f, 0.5f, torusMajor, torusMinor, 0);
    scene.finalize();
    return scene;
}

Scene transformedScene(const Scene& source, double scale, const DVec3& offset) {
    auto map = [&](const Vec3& p) { return Vec3(scale * DVec3(p) + offset); };
    Scene scene = source;
    scene.name = fmt::format("{}*{:g}+({:g},{:g},{:g})", source.name, scale, offset.x, offset.y, offset.z);
    for (Vec3& p : scene.positions) p = map(p);
    for (PointLight& light : scene.lights) light.position = map(light.position);
    if (scene.camera) {
        scene.camera->from = map(scene.camera->from);
        scene.camera->at = map(scene.camera->at);
    }
    scene.report = {};
    scene.finalize();
    return scene;
}

std::vector<Ray> raysTowardTriangles(const Scene& scene, size_t count, uint64_t seed) {
    std::vector<Ray> rays;
    if (scene.validPrimitives.empty()) return rays;
    StressRng rng(seed);
    const DVec3 centre(scene.bounds.center());
    const double radius = 0.5 * glm::length(DVec3(scene.bounds.diagonal()));
    rays.reserve(count);
    while (rays.size() < count) {
        const Triangle& tri = scene.triangles[scene.validPrimitives[rng.index(scene.validPrimitives.size())]];
        double u, v;
        do {
            u = rng.uniform();
            v = rng.uniform();
        } while (u < 0.1 || v < 0.1 || 1.0 - u - v < 0.1);
        const DVec3 q = (1.0 - u - v) * DVec3(tri.v0) + u * DVec3(tri.v1) + v * DVec3(tri.v2);
        const DVec3 n = glm::normalize(glm::cross(DVec3(tri.v1) - DVec3(tri.v0), DVec3(tri.v2) - DVec3(tri.v0)));
        const DVec3 d = rng.unitVector();
        if (std::abs(glm::dot(d, n)) < 0.2) continue;  // not within ~11.5 degrees of grazing
        const Vec3 org(q - d * (glm::length(q - centre) + radius * rng.uniform(1.1, 3.0)));
        const DVec3 dir = glm::normalize(q - DVec3(org));
        rays.push_back(Ray{org, Vec3(dir), 0.0f, kInfinity});
    }
    return rays;
}

Scene makeDistantPlaneScene(double distance, bool tilted, int cells, double size) {
    Scene scene;
    scene.name = fmt::format("plane({},{:g})", tilted ? "tilted" : "z=const", distance);
    const DVec3 centre = distance * glm::normalize(tilted ? DVec3(1.0, 0.7, 0.4) : DVec3(0.6, -0.5, 0.62));
    const DVec3 n = tilted ? glm::normalize(DVec3(0.3, 1.0, -0.45)) : DVec3(0, 0, 1);
    const DVec3 t1 = tilted ? glm::normalize(glm::cross(n, DVec3(0, 0, 1))) : DVec3(1, 0, 0);
    const DVec3 t2 = glm::cross(n, t1);
    const float planeZ = float(centre.z);
    for (int i = 0; i <= cells; ++i)
        for (int j = 0; j <= cells; ++j) {
            Vec3 p(centre + size * ((double(i) / cells - 0.5) * t1 + (double(j) / cells - 0.5) * t2));
            if (!tilted) p.z = planeZ;  // exactly one z for every vertex
            scene.positions.push_back(p);
        }
    auto at = [&](int i, int j) { return uint32_t(i * (cells + 1) + j); };
    for (int i = 0; i < cells; ++i)
        for (int j = 0; j < cells; ++j) {  // t1 x t2 = n: counter-clockwise seen from the lit side
            scene.indices.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            scene.indices.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    CameraSpec camera;
    camera.from = Vec3(centre + size * (0.9 * n + 0.1 * t1));
    camera.at = Vec3(centre);
    camera.up = Vec3(t2);
    camera.fovyDegrees = 50.0f;
    camera.width = camera.height = 64;
    scene.camera = camera;
    scene.lights = {{Vec3(centre + size * (0.6 * n - 0.2 * t2)), Vec3(1.0f)}};
    scene.finalize();
    return scene;
}

Scene makeGroundPlaneScene(double distance, double size, double elevationDegrees) {
    Scene scene;
    scene.name = fmt::format("ground({:g},{:g},{:g}deg)", distance, size, elevationDegrees);
    const DVec3 centre = distance * glm::normalize(DVec3(1.0, 0.7, 0.0));
    const double h = 0.5 * size;
    addQuad(scene, Vec3(centre + DVec3(-h, -h, 0.0)), Vec3(float(size), 0.0f, 0.0f), Vec3(0.0f, float(size), 0.0f), 0);
    CameraSpec camera;
    camera.from = Vec3(centre + DVec3(0.05 * size, 0.0, 0.6 * size));
    camera.at = Vec3(centre);
    camera.up = Vec3(0.0f, 1.0f, 0.0f);
    camera.fovyDegrees = 50.0f;
    camera.width = camera.height = 64;
    scene.camera = camera;
    const double e = glm::radians(elevationDegrees);
    scene.lights = {{Vec3(centre + 10.0 * size * DVec3(std::cos(e) * 0.6, std::cos(e) * 0.8, std::sin(e))), Vec3(1.0f)}};
    scene.finalize();
    return scene;
}

Scene makeIdenticalTrianglesScene(size_t n) {
    Scene scene;
    scene.name = fmt::format("identical{}", n);
    scene.positions = {Vec3(0.25f, 0.5f, -1.0f), Vec3(1.5f, 0.75f, -1.25f), Vec3(0.5f, 1.75f, -0.5f)};
    scene.indices.assign(n, glm::uvec3(0, 1, 2));
    scene.finalize();
    return scene;
}

void addTriangleAround(Scene& scene, StressRng& rng, const DVec3& centre, double size) {
    const DVec3 a = size * rng.unitVector(), b = size * rng.unitVector();
    addLooseTriangle(scene, Vec3(centre + a), Vec3(centre + b), Vec3(centre - a - b));
}

Scene makeTrianglesAroundScene(std::string name, size_t count, uint64_t seed,
                               const std::function<DVec3(StressRng&)>& centre,
                               const std::function<double(StressRng&)>& size) {
    StressRng rng(seed);
    Scene scene;
    scene.name = std::move(name);
    scene.positions.reserve(3 * count);
    scene.indices.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        const DVec3 c = centre(rng);  // the centre first, then the size, on every compiler
        const double s = size(rng);
        addTriangleAround(scene, rng, c, s);
    }
    scene.finalize();
    return scene;
}

Scene makeCollinearCentroidsScene(size_t n, uint64_t seed) {
    const DVec3 origin(-3.0, 1.0, 2.0), axis = glm::normalize(DVec3(1.0, 2.0, 3.0));
    return makeTrianglesAroundScene(
        fmt::format("collinear{}", n), n, seed, [&](StressRng& rng) { return origin + rng.uniform(0.0, 100.0) * axis; },
        [](StressRng& rng) { return rng.logUniform(0.01, 1.0); });
}

Scene makeHugeAmongTinyScene(size_t n, uint64_t seed) {
    StressRng rng(seed);
    Scene scene;
    scene.name = fmt::format("huge+tiny{}", n);
    scene.positions.reserve(3 * n + 3);
    scene.indices.reserve(n + 1);
    addLooseTriangle(scene, Vec3(-1000.0f, -900.0f, -800.0f), Vec3(1100.0f, -700.0f, 950.0f), Vec3(-50.0f, 1000.0f, 20.0f));
    for (size_t i = 0; i < n; ++i) {
        const DVec3 c(rng.uniform(-100, 100), rng.uniform(-100, 100), rng.uniform(-100, 100));
        const double s = 1e-3;
        addLooseTriangle(scene, Vec3(c + s * rng.unitVector()), Vec3(c + s * rng.unitVector()), Vec3(c + s * rng.unitVector()));
    }
    scene.finalize();
    return scene;
}

}  // namespace bvhlab
