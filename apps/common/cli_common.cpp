#include "apps/common/cli_common.h"

#include "accel/registry.h"
#include "apps/common/app_keys.h"
#include "apps/common/plugins.h"
#include "apps/common/program_keys.h"
#include "framework/config/common_keys.h"
#include "framework/config/install_paths.h"
#include "framework/core/error.h"
#include "framework/core/timed_build.h"
#include "framework/scene/procedural.h"
#include "framework/scene/scene_cache.h"
#include "framework/scene/scene_loader.h"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>

#include <unistd.h>

namespace bvhlab {

void EnvOptions::addTo(CLI::App& command) {
    command.add_option("--env", envFiles,
                       "env file(s) layered on env/global.env (and the scene's env file), later ones win");
    command.add_option("-D", overrides, "override an env key: -DSection::key=value (repeatable; wins over files)")
        ->allow_extra_args(false);
    command.add_flag("--no-global-env", noGlobalEnv, "do not read env/global.env: start from the keys' defaults");
    command.add_option("--plugin", plugins, "load a plugin's accelerators from this file (repeatable; docs/plugins.md)");
}

void EnvOptions::addThreadsTo(CLI::App& command) {
    command.add_option("--threads", threads, "threads (SetRayTracing::threads); 0 = all hardware threads")
        ->check(CLI::Range(0, 1024));
}

std::vector<std::string> EnvOptions::files(const std::filesystem::path& sceneEnvFile) const {
    std::vector<std::string> candidates;
    if (!noGlobalEnv) candidates.push_back(dataFile("env/global.env").string());
    if (!sceneEnvFile.empty()) candidates.push_back(sceneEnvFile.string());
    candidates.insert(candidates.end(), envFiles.begin(), envFiles.end());
    // A file named twice (--env env/global.env) is read once, where it first comes.
    std::vector<std::string> result;
    for (const std::string& file : candidates) {
        std::error_code ec;
        const bool seen = std::any_of(result.begin(), result.end(), [&](const std::string& earlier) {
            return std::filesystem::equivalent(earlier, file, ec);
        });
        if (!seen) result.push_back(file);
    }
    return result;
}

void EnvOptions::loadPlugins(const std::vector<std::string>& layerFiles) const {
    for (const std::string& file : plugins) loadPlugin(file);
    // ASDS::plugins and ASDS::type as the layers give them, read before the registry checks the
    // layers, since a plugin they name adds keys and accelerators the layers may use.
    struct Assignment {
        EnvLine line;
        std::filesystem::path baseDir;  // relative plugin files resolve against it
    };
    std::vector<Assignment> assignments;
    for (const std::string& file : layerFiles)
        for (const EnvLine& line : readEnvLines(file))
            assignments.push_back({line, std::filesystem::absolute(file).parent_path()});
    for (const std::string& assignment : overrides) {
        const size_t eq = assignment.find('=');
        if (eq == std::string::npos) continue;  // reported by Env::setOverride
        const std::string name = assignment.substr(0, eq);
        assignments.push_back({{name, assignment.substr(eq + 1), "-D" + name}, std::filesystem::current_path()});
    }
    std::string type, typeOrigin;
    for (const auto& [line, baseDir] : assignments) {
        if (line.name == keys::ASDS::plugins.name())
            for (const std::string& file : splitCommaList(line.text)) loadPlugin(baseDir / file);
        if (line.name == keys::ASDS::type.name() && !line.text.empty()) std::tie(type, typeOrigin) = std::pair(line.text, line.origin);
    }
    for (const std::string& name : accelerators) loadPluginFor(name);  // unknown: the command says so
    if (!type.empty() && !loadPluginFor(type)) throw InputError(fmt::format("{}: {}", typeOrigin, unknownAcceleratorMessage(type)));
    for (const auto& [line, baseDir] : assignments) checkKeyIsNotAnUnloadedPlugins(line.name, line.origin);
}

Env EnvOptions::load(const std::filesystem::path& sceneEnvFile) const {
    loadPlugins(files(sceneEnvFile));
    Env env(programKeys());
    for (const std::string& file : files(sceneEnvFile)) env.loadFile(file);
    if (threads >= 0) env.set(keys::SetRayTracing::threads, std::to_string(threads), "--threads");
    for (const std::string& assignment : overrides) env.setOverride(assignment);
    return env;
}

std::filesystem::path sceneEnvFor(const std::filesystem::path& sceneFile, const EnvOptions& options) {
    const std::filesystem::path folder = dataFile("env/scenes");
    if (!std::filesystem::is_directory(folder)) return {};
    std::vector<std::filesystem::path> candidates;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
        if (entry.path().extension() == ".env") candidates.push_back(entry.path());
    std::sort(candidates.begin(), candidates.end());
    std::error_code ec;
    for (const std::filesystem::path& candidate : candidates) {
        const Env env = options.load(candidate);
        if (env.get(keys::Scene::file).empty()) continue;
        if (std::filesystem::equivalent(env.get(keys::Scene::dir) / env.get(keys::Scene::file), sceneFile, ec))
            return candidate;
    }
    return {};
}

SceneChoice chooseScene(const std::string& scene, const std::string& sceneEnv, const EnvOptions& options) {
    SceneChoice choice;
    if (!sceneEnv.empty()) {
        if (!std::filesystem::is_regular_file(sceneEnv))
            throw InputError(fmt::format("--scene-env {}: no such file", sceneEnv));
        choice.envFile = sceneEnv;
    }
    if (scene.empty()) return choice;
    // A file here, or in Scene::dir as -DScene::file would find it.
    const std::filesystem::path inSceneDir = options.load().get(keys::Scene::dir) / scene;
    for (const std::filesystem::path& file : {std::filesystem::path(scene), inSceneDir}) {
        if (!std::filesystem::is_regular_file(file)) continue;
        choice.sceneFile = file;
        if (choice.envFile.empty()) choice.envFile = sceneEnvFor(file, options);
        return choice;
    }
    const std::filesystem::path named = dataFile(std::filesystem::path("env/scenes") / (scene + ".env"));
    if (scene.find('/') == std::string::npos && std::filesystem::is_regular_file(named)) {
        if (choice.envFile.empty()) choice.envFile = named;
        return choice;
    }
    std::vector<std::string> known;
    if (std::filesystem::is_directory(dataFile("env/scenes")))
        for (const auto& entry : std::filesystem::directory_iterator(dataFile("env/scenes")))
            if (entry.path().extension() == ".env") known.push_back(entry.path().stem().string());
    std::sort(known.begin(), known.end());
    throw InputError(fmt::format("--scene {}: no such file here or in Scene::dir ({}), and no scene env file "
                                 "env/scenes/{}.env (scene names: {})",
                                 scene, inSceneDir.parent_path().string(), scene, fmt::join(known, ", ")));
}

Env SceneChoice::load(const EnvOptions& options) const {
    Env env = options.load(envFile);
    if (!sceneFile.empty())
        env.set(keys::Scene::file, std::filesystem::absolute(sceneFile).lexically_normal().string(), "--scene");
    return env;
}

Scene loadSceneFor(const Env& env, bool useCache, SceneLoadInfo* info) {
    // Relative to Scene::dir; an absolute Scene::file (as --scene sets it) stays as it is.
    const std::filesystem::path path = env.get(keys::Scene::file).empty()
                                           ? std::filesystem::path()
                                           : env.get(keys::Scene::dir) / env.get(keys::Scene::file);
    const std::filesystem::path cacheDir = useCache ? env.get(keys::Scene::cacheDir) : std::filesystem::path();
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

BuiltAccelerator buildAccelerator(const Scene& scene, const Env& env) {
    BuiltAccelerator built{createAccelerator(env), {}};
    built.stats = timedBuild(*built.accel, scene.primitives());
    fmt::print(stderr, "{}: built over {} primitives in {:.1f} ms\n", built.accel->name(), built.stats.primitives,
               built.stats.buildMs);
    return built;
}

RenderStats renderWithProgress(const Scene& scene, const Accelerator& accel, const Camera& camera,
                               const RenderSettings& settings, Framebuffer& fb, Progress& progress,
                               const std::string& label) {
    progress.phase(label, tileCount(fb.width, fb.height));
    const RenderStats stats = render(scene, accel, camera, settings, fb, [&](uint64_t rays) { progress.advance(1, rays); });
    progress.finish();
    return stats;
}

std::filesystem::path prepareOutputFile(const std::string& path, const std::string& option) {
    const std::filesystem::path file = path;
    if (path.empty()) throw InputError(option + ": empty path (give a file, e.g. out/render)");
    if (!file.has_filename() || file.filename() == "." || file.filename() == ".." || std::filesystem::is_directory(file))
        throw InputError(fmt::format("{} {}: names a folder; give a file in it, e.g. {}", option, path,
                                     (file / "render").lexically_normal().string()));
    if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
    return file;
}

std::filesystem::path prepareOutputFolder(const std::string& path, const std::string& option) {
    if (path.empty()) throw InputError(option + ": empty path (give a folder, e.g. out/batch)");
    const std::filesystem::path folder = path;
    if (std::filesystem::exists(folder) && !std::filesystem::is_directory(folder))
        throw InputError(fmt::format("{} {}: is a file, not a folder", option, path));
    std::filesystem::create_directories(folder);
    return folder;
}

std::vector<std::string> splitCommaList(const std::string& text) {
    std::vector<std::string> items;
    std::string item;
    for (std::stringstream in(text); std::getline(in, item, ',');) {
        item.erase(0, item.find_first_not_of(" \t"));
        item.erase(item.find_last_not_of(" \t") + 1);
        if (!item.empty()) items.push_back(item);
    }
    return items;
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

ChosenScene loadChosenScene(const std::string& scene, const EnvOptions& options, const std::string& out,
                            Progress& progress) {
    Env env = chooseScene(scene, "", options).load(options);
    prepareOutputFile(out);
    progress.phase("loading the scene");
    Scene loaded = loadSceneFor(env);
    return {std::move(env), std::move(loaded)};
}

std::string overrideWithoutEqualsHint(int argc, const char* const* argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (!arg.starts_with("-D") || arg.starts_with("--")) continue;
        // -DKey or -D Key, then a word that is not an option.
        const int keyAt = arg == "-D" ? i + 1 : i;
        if (keyAt + 1 >= argc) continue;
        const std::string_view key = arg == "-D" ? std::string_view(argv[keyAt]) : arg.substr(2);
        const std::string_view value = argv[keyAt + 1];
        if (key.find('=') != std::string_view::npos || value.starts_with('-')) continue;
        return fmt::format("-D{} {}: -D takes Section::key=value as one word; write -D{}={}", key, value, key, value);
    }
    return {};
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
