#include "accel/verify/stress_scenes.h"

#include "framework/scene/procedural.h"

#include <fmt/format.h>

namespace bvhlab::verify {

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
    scene.lights = {
        {Vec3(centre + 10.0 * size * DVec3(std::cos(e) * 0.6, std::cos(e) * 0.8, std::sin(e))), Vec3(1.0f)}};
    scene.finalize();
    return scene;
}

std::vector<double> sweepScales() { return {1e-3, 0x1p-10, 1e-2, 1e-1, 1.0, 1e1, 1e2, 1e3, 0x1p13, 1e4}; }

std::vector<DVec3> sweepOffsets() {
    return {DVec3(0), DVec3(10, 0, 0), DVec3(0, -10, 0), DVec3(0, 0, 10), DVec3(-10, 10, -10)};
}

std::vector<AcneCase> acneCases() {
    std::vector<AcneCase> cases;
    for (double distance : {1e4, 1e6})
        for (bool tilted : {true, false})
            cases.push_back({makeDistantPlaneScene(distance, tilted), distance, distance == 1e4, true});
    for (const auto& [distance, size] : {std::pair{800.0, 600.0}, std::pair{0.0, 2e4}})
        cases.push_back({makeGroundPlaneScene(distance, size, 5.0), distance, true, false});
    return cases;
}

}  // namespace bvhlab::verify
