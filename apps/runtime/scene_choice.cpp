#include "apps/runtime/scene_choice.h"

#include "apps/runtime/app_keys.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/run_record.h"
#include "apps/runtime/scene_loading.h"
#include "framework/config/install_paths.h"
#include "framework/core/error.h"
#include "framework/scene/scene_loader.h"

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
    // By the file's name, so that the scene's copy anywhere (an installed bvhlab's Scene::dir
    // need not hold it) is seen as its env file says; the env file naming this very file wins a tie.
    std::vector<std::filesystem::path> sameName, sameFile;
    std::error_code ec;
    for (const std::filesystem::path& candidate : candidates) {
        const Env env = options.load(candidate);
        const std::filesystem::path named = env.get(keys::Scene::file);
        if (named.empty() || uncompressedName(named) != uncompressedName(sceneFile)) continue;
        sameName.push_back(candidate);
        if (std::filesystem::equivalent(env.get(keys::Scene::dir) / named, sceneFile, ec))
            sameFile.push_back(candidate);
    }
    if (sameName.size() == 1) return sameName.front();
    if (sameFile.size() == 1) return sameFile.front();
    if (sameName.empty()) return {};
    std::vector<std::string> names;
    for (const std::filesystem::path& candidate : sameName) names.push_back(candidate.string());
    throw InputError(
        fmt::format("{}: the scene env files {} all name a scene file {}; say which one to use (--scene-env "
                    "FILE, or the env file in --scenes instead of the scene file)",
                    sceneFile.string(), fmt::join(names, ", "), uncompressedName(sceneFile).string()));
}

void warnOfMissingSceneEnv(const std::filesystem::path& sceneFile) {
    warnOfRun(
        fmt::format("{}: no scene env file in {} names {}, so it is seen without one: the camera and lights of "
                    "env/global.env, --env and -D over the scene file's own (NFF, AFF), else a view framing the "
                    "scene and one light above the camera",
                    sceneFile.string(), dataFile("env/scenes").string(), uncompressedName(sceneFile).string()));
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
    const Env env = options.load();
    const std::filesystem::path inSceneDir = env.get(keys::Scene::dir) / scene;
    for (const std::filesystem::path& file : {std::filesystem::path(scene), inSceneDir}) {
        if (!std::filesystem::is_regular_file(file)) continue;
        choice.sceneFile = file;
        if (choice.envFile.empty()) choice.envFile = sceneEnvFor(file, options);
        if (choice.envFile.empty()) warnOfMissingSceneEnv(file);
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
    throw InputError(
        fmt::format("--scene {}: no such file here or in Scene::dir, and no scene env file "
                    "env/scenes/{}.env (scene names: {}). {}",
                    scene, scene, fmt::join(known, ", "), env.howToSet(keys::Scene::dir)));
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
