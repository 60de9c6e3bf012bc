// The scenes of `bvhlab check --scene`, each read through its scene's env (an animated one at
// Scene::frame), for the checks that take scenes (verify::UserScene).
#pragma once

#include "accel/verify/conformance.h"
#include "apps/runtime/env_options.h"
#include "framework/scene/scene.h"

#include <nlohmann/json.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bvhlab::check {

// One scene of --scene, read: at its frame and, if it is animated, at the next frame (the previous
// one at the last) for the update check.
struct CheckScene {
    // Its file's name (else its env file's), "at frame K" after it when animated: never a generated
    // scene's name, which has no dot.
    std::string name;
    std::string fileName;  // the file's name alone
    Scene scene;
    int frameCount = 1;
    std::optional<int> frame, movedFrame;  // an animated scene's frame, and the update check's other one
    std::optional<Scene> moved;            // at movedFrame
};

// Reads the scenes the arguments name, as other commands' --scenes take them (apps/runtime/
// scene_list.h): repeatable, comma-separated. Throws InputError naming the file that is missing or
// malformed, or the frame past an animation's last.
std::vector<std::shared_ptr<const CheckScene>> readCheckScenes(const std::vector<std::string>& arguments,
                                                               const EnvOptions& options);

// The scenes as the checks take them: each factory copies the scene read.
std::vector<verify::UserScene> userScenes(const std::vector<std::shared_ptr<const CheckScene>>& scenes);

// What --json says of a scene: its name, file, frame, the update check's other frame, and counts.
nlohmann::json toJson(const CheckScene& scene);

}  // namespace bvhlab::check
