#include "apps/runtime/scene_loading.h"

#include "apps/runtime/app_keys.h"
#include "apps/runtime/run_record.h"
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

namespace {

// The animated scene of `path` at the frame Scene::frame names.
AnimatedScene loadAtFrame(const std::filesystem::path& path, const Env& env) {
    AnimatedScene animated = loadAnimatedScene(path);
    const int frame = env.get(keys::Scene::frame);
    if (frame >= animated.frameCount)
        throw InputError(fmt::format("Scene::frame {} (from {}): {} has {} frame{}, 0 to {}", frame,
                                     env.origin(keys::Scene::frame.name()), path.filename().string(),
                                     animated.frameCount, animated.frameCount == 1 ? "" : "s",
                                     animated.frameCount - 1));
    if (frame > 0) animated.setTime(animated.frameTime(frame));
    return animated;
}

void warnOfIgnoredFrame(const Env& env, const Scene& scene) {
    const int frame = env.get(keys::Scene::frame);
    if (frame != 0)
        warnOfRun(fmt::format("Scene::frame {} (from {}) ignored: {} is a still scene", frame,
                              env.origin(keys::Scene::frame.name()), scene.name));
}

// Says on stderr what the load met.
void reportLoad(const Scene& scene, const SceneLoadInfo& loaded) {
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
}

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Scene loadSceneFor(const Env& env, bool useCache, SceneLoadInfo* info) {
    const std::filesystem::path path = sceneFileOf(env);
    const std::filesystem::path cacheDir = useCache ? env.get(keys::Scene::cacheDir) : std::filesystem::path();
    SceneLoadInfo loaded;
    const auto start = std::chrono::steady_clock::now();
    Scene scene;
    if (path.empty()) {
        scene = makeDefaultScene();
    } else if (isAnimatedScene(path)) {
        scene = std::move(loadAtFrame(path, env).scene);
    } else if (cacheDir.empty() || readsOtherFiles(path)) {
        scene = loadScene(path);
    } else {
        CachedScene cached = loadSceneCached(path, cacheDir);
        if (!cached.note.empty()) fmt::print(stderr, "scene cache: {}\n", cached.note);
        scene = std::move(cached.scene);
        loaded.fromCache = cached.fromCache;
        loaded.cacheFile = cached.cacheFile;
    }
    loaded.ms = msSince(start);
    reportLoad(scene, loaded);
    if (!isAnimatedScene(path)) warnOfIgnoredFrame(env, scene);
    if (info) *info = loaded;
    return scene;
}

AnimatedScene loadAnimatedSceneFor(const Env& env) {
    const std::filesystem::path path = sceneFileOf(env);
    const auto start = std::chrono::steady_clock::now();
    AnimatedScene animated;
    if (!path.empty() && isAnimatedScene(path)) {
        animated = loadAtFrame(path, env);
    } else {
        animated.scene = path.empty() ? makeDefaultScene() : loadScene(path);
        animated.prepare();
    }
    SceneLoadInfo loaded;
    loaded.ms = msSince(start);
    reportLoad(animated.scene, loaded);
    if (path.empty() || !isAnimatedScene(path)) warnOfIgnoredFrame(env, animated.scene);
    return animated;
}

}  // namespace bvhlab
