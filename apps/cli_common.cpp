#include "apps/cli_common.h"

#include "accel/registry.h"
#include "framework/error.h"
#include "framework/procedural.h"
#include "framework/scene_cache.h"
#include "framework/scene_loader.h"

#include <fmt/core.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include <unistd.h>

namespace bvhlab {

void EnvOptions::addTo(CLI::App& command) {
    command.add_option("--env", envFiles, "env file(s), later ones override earlier ones (default env/global.env)");
    command.add_option("-D", overrides, "override an env key: -DSection::key=value (repeatable; wins over files)")
        ->allow_extra_args(false);
}

Env EnvOptions::load(const std::vector<std::string>& extraFiles) const {
    Env env;
    std::vector<std::string> files = envFiles;
    if (files.empty()) {
        // The default env file is the repository's, wherever bvhlab is run from.
        const std::filesystem::path local = "env/global.env";
        files.push_back(std::filesystem::exists(local) ? local.string()
                                                      : (std::filesystem::path(BVHLAB_SOURCE_DIR) / local).string());
    }
    files.insert(files.end(), extraFiles.begin(), extraFiles.end());
    for (const std::string& file : files) env.loadFile(file);
    for (const std::string& assignment : overrides) env.setOverride(assignment);
    return env;
}

Scene loadSceneFor(const std::string& file, const Env& env, bool useCache, SceneLoadInfo* info) {
    // A file named on the command line is relative to the working folder, one named in env
    // to Scene::dir (absolute paths stay as they are).
    const std::filesystem::path path =
        !file.empty() ? std::filesystem::path(file)
        : env.getString("Scene::file").empty() ? std::filesystem::path()
                                                : env.getPath("Scene::dir") / env.getString("Scene::file");
    const std::filesystem::path cacheDir = useCache ? env.getPath("Scene::cacheDir") : std::filesystem::path();
    SceneLoadInfo loaded;
    const auto start = std::chrono::steady_clock::now();
    Scene scene;
    if (path.empty()) {
        scene = makeDefaultScene();
    } else if (cacheDir.empty()) {
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
    if (scene.report.unsupportedSpheres || scene.report.unsupportedCones)
        fmt::print(stderr, "scene {}: not yet supported and not rendered: {} spheres, {} cones/cylinders\n",
                   scene.name, scene.report.unsupportedSpheres, scene.report.unsupportedCones);
    for (const std::string& warning : scene.report.warnings) fmt::print(stderr, "warning: {}\n", warning);
    if (info) *info = loaded;
    return scene;
}

BuiltAccelerator buildAccelerator(const Scene& scene, const Env& env) {
    BuiltAccelerator built{createAccelerator(env), {}};
    built.stats = built.accel->build(scene.primitives());
    fmt::print(stderr, "{}: built over {} primitives in {:.1f} ms\n", built.accel->name(), built.stats.primitives,
               built.stats.buildMs);
    return built;
}

void writeFileAtomically(const std::filesystem::path& file, const std::string& text) {
    const std::filesystem::path temporary = file.string() + fmt::format(".tmp-{}", ::getpid());
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << text;
        if (!out) throw InputError(fmt::format("{}: cannot write", temporary.string()));
    }
    std::filesystem::rename(temporary, file);
}

int runGuarded(const std::function<void()>& body) {
    try {
        body();
        return 0;
    } catch (const InputError& e) {
        fmt::print(stderr, "error: {}\n", e.what());
    } catch (const std::exception& e) {
        fmt::print(stderr, "error: {}\n", e.what());
    }
    return 1;
}

}  // namespace bvhlab
