// Which scene a run reads and the env it runs with: a scene file, or a scene's name for its env
// file under env/scenes/, each seen from its own camera with its own lights.
#pragma once

#include "apps/runtime/env_options.h"
#include "apps/runtime/progress.h"
#include "framework/scene/scene.h"

#include <filesystem>
#include <string>

namespace bvhlab {

// The env file under env/scenes/ whose Scene::file has the name of `sceneFile` (a10.obj for
// /anywhere/a10.obj or a10.obj.gz), or empty: so a scene named by its file is seen from its own
// camera with its own lights wherever the file lives. Of several such env files, the one whose
// Scene::dir holds this very file; else throws InputError naming them.
std::filesystem::path sceneEnvFor(const std::filesystem::path& sceneFile, const EnvOptions& options);

// Says on stderr and in the run's JSON (warnOfRun) that `sceneFile` has no scene env file.
void warnOfMissingSceneEnv(const std::filesystem::path& sceneFile);

// What `--scene X [--scene-env F]` names. X is a scene file, or NAME for env/scenes/NAME.env.
struct SceneChoice {
    std::filesystem::path sceneFile;  // empty: the env's Scene::file
    std::filesystem::path envFile;    // the scene's env file; empty: none
    // The layered env, with Scene::file set to the file actually read.
    Env load(const EnvOptions& options) const;
};
SceneChoice chooseScene(const std::string& scene, const std::string& sceneEnv, const EnvOptions& options);

// The scene `--scene` names (chooseScene, no --scene-env) with the env it runs with, loaded
// after `out` is checked (so a bad output path fails before the load), the load shown on `progress`.
struct ChosenScene {
    Env env;
    Scene scene;
};
ChosenScene loadChosenScene(const std::string& scene, const EnvOptions& options, const std::string& out,
                            Progress& progress);

}  // namespace bvhlab
