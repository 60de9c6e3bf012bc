// Scene folders for the batch tests, in the test's scratch folder: OBJ files, each with its env
// file (camera, lights), and a scenes.list of them.
#pragma once

#include "framework/scene/procedural.h"
#include "tests/support/scratch_dir.h"

#include <filesystem>
#include <fstream>
#include <string>

namespace bvhlab::test {

// The scene's vertices and triangles as an OBJ file.
inline void writeObj(const std::filesystem::path& file, const Scene& scene) {
    std::ofstream out(file);
    for (const Vec3& p : scene.positions) out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const glm::uvec3& t : scene.indices) out << "f " << t.x + 1 << ' ' << t.y + 1 << ' ' << t.z + 1 << '\n';
}

// A fresh folder scratchDir("batch")/NAME holding two tiny scenes (first: a ground quad and a
// tetrahedron, 6 triangles; second: the same and a wedge, 8) and scenes.list of both.
inline std::filesystem::path makeScenes(const std::string& name) {
    const std::filesystem::path dir = scratchDir("batch") / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string ground = "v -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nf 1 3 2\nf 1 4 3\n";
    const std::string tetra = "v 0 0.5 0\nv 1 0.5 0\nv 0 1.5 0\nv 0 0.5 1\nf 5 6 7\nf 5 8 6\nf 5 7 8\nf 6 8 7\n";
    std::ofstream(dir / "first.obj") << ground << tetra;
    std::ofstream(dir / "second.obj") << ground << tetra << "v -2 0 -2\nv -1 0 -2\nv -2 1 -2\nf 9 10 11\nf 9 11 10\n";
    std::ofstream(dir / "first.env") << "Scene::file first.obj\nScene::dir .\nCamera::from 3 3 3\nCamera::at 0 0.5 0\n"
                                        "Camera::width 24\nCamera::height 18\nLights::positions 2 6 1\n";
    std::ofstream(dir / "second.env")
        << "Scene::file second.obj\nScene::dir .\nCamera::from -3 2 3\nCamera::at 0 0.5 0\n"
           "Camera::width 20\nCamera::height 20\nLights::positions -1 5 2, 3 4 3\n";
    std::ofstream(dir / "scenes.list") << "# two tiny scenes\nfirst.env\nsecond.env\n";
    return dir;
}

// `bvhlab batch` over makeScenes' folder with naive and sahbvh, its own scene cache, into DIR/OUT.
inline std::string batchArgs(const std::filesystem::path& dir, const std::string& out) {
    return "batch --scenes " + (dir / "scenes.list").string() +
           " --accel naive,sahbvh -DScene::cacheDir=" + (dir / "cache").string() + " --out " + (dir / out).string();
}

// A fresh folder scratchDir("batch")/NAME holding three small generated scenes on a floor
// (spheres: three icospheres of `sphereSubdivisions`, 1280 triangles each at 3; torus: 2304
// triangles; boxes: 60) and scenes.list of them in that order.
inline std::filesystem::path makeSolidScenes(const std::string& name, int sphereSubdivisions = 3) {
    const std::filesystem::path dir = scratchDir("batch") / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    Scene spheres, torus, boxes;
    for (Scene* scene : {&spheres, &torus, &boxes}) addQuad(*scene, Vec3(-4, 0, -4), Vec3(0, 0, 8), Vec3(8, 0, 0), 0);
    for (int i = 0; i < 3; ++i)
        addIcosphere(spheres, Vec3(-2.0f + 2.0f * i, 0.8f, 0.5f * i), 0.8f, sphereSubdivisions, 0);
    addTorus(torus, Vec3(0, 0.6f, 0), 1.5f, 0.5f, 48, 24, 0);
    for (int i = 0; i < 5; ++i)
        addBox(boxes, Vec3(-3.0f + 1.3f * i, 0, -0.5f), Vec3(-2.2f + 1.3f * i, 0.5f + 0.4f * i, 0.5f), 0);
    writeObj(dir / "spheres.obj", spheres);
    writeObj(dir / "torus.obj", torus);
    writeObj(dir / "boxes.obj", boxes);
    for (const char* scene : {"spheres", "torus", "boxes"})
        std::ofstream(dir / (std::string(scene) + ".env"))
            << "Scene::file " << scene << ".obj\nScene::dir .\nCamera::from 4 4 6\nCamera::at 0 0.5 0\n"
            << "Lights::positions 3 8 4, -5 6 2\n";
    std::ofstream(dir / "scenes.list") << "# three small generated scenes\nspheres.env\ntorus.env\nboxes.env\n";
    return dir;
}

}  // namespace bvhlab::test
