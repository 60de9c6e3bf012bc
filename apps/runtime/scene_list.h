// The scenes a batch, bench, tradeoff or stress run goes over, as --scenes names them: scene
// env files (.env: camera, lights, Scene::file), .list files of env files (one per line,
// relative to the list's folder, `#` comments), scene files (.obj .ply .off .nff .aff, .gz; here or
// in Scene::dir), each taken with the env file under env/scenes/ that names it (sceneEnvFor),
// or scenes' names (teapots for env/scenes/teapots.env), as --scene takes them (chooseScene).
#pragma once

#include "apps/runtime/env_options.h"
#include "framework/config/env.h"

#include <filesystem>
#include <string>
#include <vector>

namespace bvhlab {

struct SceneArgument {
    std::string id;                   // the env file's stem, else the scene file's, else the name: names jobs and rows
    std::filesystem::path envFile;    // the scene's env file; empty for a scene file no env file names
    std::filesystem::path sceneFile;  // the scene file named directly; empty when the env file names it

    // The layered env of this scene (SceneChoice::load).
    Env load(const EnvOptions& options) const;
};

// Expands the arguments (--scenes is repeatable, and each may also be a comma-separated list);
// with none, env/scenes.list of the repository. Throws InputError for a missing file or scene
// name, or two scenes of one id.
std::vector<SceneArgument> expandSceneList(const std::vector<std::string>& arguments, const EnvOptions& options);

}  // namespace bvhlab
