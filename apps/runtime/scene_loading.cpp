#include "apps/runtime/scene_loading.h"

#include "apps/runtime/app_keys.h"
#include "framework/core/error.h"
#include "framework/scene/procedural.h"
#include "framework/scene/scene_cache.h"
#include "framework/scene/scene_loader.h"

#include <fmt/core.h>

#include <chrono>
#include <string>

namespace bvhlab {

std::filesystem::path sceneFileOf(const Env& env) {
    const std::filesystem::path file = env.get(keys::Scene::file);
    if (file.empty()) return {};
    // Relative to Scene::dir; an absolute Scene::file (as --scene sets it) stays as it is.
    const std::filesystem::path path = env.get(keys::Scene::dir) / file;
    std::error_code ec;
    if (file.is_relative() && !std::filesystem::exists(path, ec))
        throw InputError(fmt::format("scene file {} (Scene::file, from {}): no such file {}; {}", file.string(),
                                     env.origin(keys::Scene::file.name()), path.string(),
                                     env.howToSet(keys::Scene::dir)));
    return path;
}

Scene loadSceneFor(const Env& env, bool useCache, SceneLoadInfo* info) {
    const std::filesystem::path path = sceneFileOf(env);
    const std::filesystem::path cacheDir = useCache ? env.get(keys::Scene::cacheDir) : std::filesystem::path();
    SceneLoadInfo loaded;
    const auto start = std::chrono::steady_clock::now();
    Scene scene;
    if (path.empty()) {
        scene = makeDefaultScene();
    } else if (cacheDir.empty() || readsOtherFiles(path)) {
        scene = loadScene(path);
    } else {
        CachedScene cached = loadSceneCached(path, cacheDir);
        if (!cached.note.empty()) fmt::print(stderr, "scene cache: {}\n", cached.note);
        scene = std::move(cached.scene);
        loaded.fromCache = cached.fromCache;
        loaded.cacheFile = cached.cacheFile;
    }
    loaded.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    fmt::print(stderr, "scene {}: {} triangles ({} degenerate, not built over) {} in {:.0f} ms\n", scene.name,
               scene.triangleCount(), scene.report.degenerateTriangles,
               loaded.fromCache ? "read from cache " + loaded.cacheFile.string() : std::string("loaded"), loaded.ms);
    if (scene.report.skippedPolygons || scene.report.earClippedPolygons)
        fmt::print(stderr, "scene {}: {} non-convex polygons ear-clipped, {} polygons skipped (no exact cover)\n",
                   scene.name, scene.report.earClippedPolygons, scene.report.skippedPolygons);
    if (!scene.spheres.empty() || !scene.cones.empty())
        fmt::print(stderr, "scene {}: {} spheres ({} degenerate), {} cones/cylinders ({} degenerate)\n", scene.name,
                   scene.spheres.size(), scene.report.degenerateSpheres, scene.cones.size(),
                   scene.report.degenerateCones);
    for (const std::string& warning : scene.report.warnings) fmt::print(stderr, "warning: {}\n", warning);
    if (info) *info = loaded;
    return scene;
}

}  // namespace bvhlab
