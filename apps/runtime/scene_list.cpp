#include "apps/runtime/scene_list.h"

#include "apps/runtime/comma_list.h"
#include "apps/runtime/scene_choice.h"
#include "framework/config/install_paths.h"
#include "framework/core/error.h"

#include <fmt/core.h>

#include <algorithm>
#include <fstream>

namespace bvhlab {

Env SceneArgument::load(const EnvOptions& options) const { return SceneChoice{sceneFile, envFile}.load(options); }

std::vector<SceneArgument> expandSceneList(const std::vector<std::string>& arguments, const EnvOptions& options) {
    std::vector<std::string> items;
    for (const std::string& argument : arguments)
        for (const std::string& item : splitCommaList(argument)) items.push_back(item);
    if (items.empty()) items.push_back(dataFile("env/scenes.list").string());

    std::vector<SceneArgument> scenes;
    auto add = [&](SceneArgument scene, const std::string& given) {
        if (std::any_of(scenes.begin(), scenes.end(), [&](const SceneArgument& s) { return s.id == scene.id; }))
            throw InputError(
                fmt::format("--scenes: two scenes are named '{}' ({}): jobs and rows are named by the "
                            "file's stem",
                            scene.id, given));
        scenes.push_back(std::move(scene));
    };
    for (const std::filesystem::path item : items) {
        if (item.extension() == ".env") {
            if (!std::filesystem::is_regular_file(item))
                throw InputError(fmt::format("--scenes {}: no such file", item.string()));
            add({item.stem().string(), item, {}}, item.string());
            continue;
        }
        if (item.extension() != ".list") {
            // A scene file (here or in Scene::dir) or a scene's name, as --scene takes them.
            const SceneChoice choice = chooseScene(item.string(), "", options);
            // munich.ply.gz and munich.ply are both "munich".
            std::filesystem::path stem = choice.sceneFile.filename();
            while (stem.has_extension()) stem = stem.stem();
            add({choice.sceneFile.empty() ? item.string() : stem.string(), choice.envFile, choice.sceneFile},
                item.string());
            continue;
        }
        std::ifstream in(item);
        if (!in) throw inputError(item, 0, "cannot open scene list");
        std::string line;
        for (size_t lineNo = 1; std::getline(in, line); ++lineNo) {
            line = line.substr(0, line.find('#'));
            line.erase(0, line.find_first_not_of(" \t\r"));
            line.erase(line.find_last_not_of(" \t\r") + 1);
            if (line.empty()) continue;
            const std::filesystem::path file = item.parent_path() / line;
            if (!std::filesystem::exists(file)) throw inputError(item, lineNo, "no such env file: " + file.string());
            add({file.stem().string(), file, {}}, file.string());
        }
    }
    return scenes;
}

}  // namespace bvhlab
