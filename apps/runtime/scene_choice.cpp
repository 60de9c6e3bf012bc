#include "apps/runtime/scene_choice.h"

#include "apps/runtime/app_keys.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/scene_loading.h"
#include "framework/config/install_paths.h"
#include "framework/core/error.h"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <vector>

namespace bvhlab {

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

ChosenScene loadChosenScene(const std::string& scene, const EnvOptions& options, const std::string& out,
                            Progress& progress) {
    Env env = chooseScene(scene, "", options).load(options);
    prepareOutputFile(out);
    progress.phase("loading the scene");
    Scene loaded = loadSceneFor(env);
    return {std::move(env), std::move(loaded)};
}

}  // namespace bvhlab
