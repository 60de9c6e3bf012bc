#include "apps/check/check_scenes.h"

#include "apps/runtime/app_keys.h"
#include "apps/runtime/run_record.h"
#include "apps/runtime/scene_list.h"
#include "apps/runtime/scene_loading.h"

#include <fmt/format.h>

#include <filesystem>

namespace bvhlab::check {

std::vector<std::shared_ptr<const CheckScene>> readCheckScenes(const std::vector<std::string>& arguments,
                                                               const EnvOptions& options) {
    std::vector<std::shared_ptr<const CheckScene>> scenes;
    if (arguments.empty()) return scenes;  // expandSceneList would take env/scenes.list
    for (const SceneArgument& argument : expandSceneList(arguments, options)) {
        const Env env = argument.load(options);
        const std::filesystem::path file = sceneFileOf(env);
        AnimatedScene animated = loadAnimatedSceneFor(env);
        auto read = std::make_shared<CheckScene>();
        read->fileName = read->name = (file.empty() ? argument.envFile : file).filename().string();
        read->frameCount = animated.frameCount;
        if (animated.frameCount > 1) {
            const int frame = env.get(keys::Scene::frame);
            read->name += fmt::format(" at frame {}", frame);
            read->frame = frame;
            read->movedFrame = frame + 1 < animated.frameCount ? frame + 1 : frame - 1;
            read->scene = animated.scene;
            animated.setTime(animated.frameTime(*read->movedFrame));
            read->moved = std::move(animated.scene);
        } else {
            read->scene = std::move(animated.scene);
        }
        scenes.push_back(std::move(read));
    }
    return scenes;
}

std::vector<verify::UserScene> userScenes(const std::vector<std::shared_ptr<const CheckScene>>& scenes) {
    std::vector<verify::UserScene> users;
    for (const std::shared_ptr<const CheckScene>& read : scenes) {
        verify::UserScene user;
        user.scene = {read->name, [read] { return read->scene; }};
        if (read->moved) {
            user.moved = {fmt::format("{} from frame {} to {}", read->fileName, *read->frame, *read->movedFrame),
                          [read] { return *read->moved; }};
        }
        users.push_back(std::move(user));
    }
    return users;
}

nlohmann::json toJson(const CheckScene& scene) {
    const auto orNull = [](const std::optional<int>& value) { return value ? nlohmann::json(*value) : nullptr; };
    nlohmann::json json = {{"name", scene.name},
                           {"frame", orNull(scene.frame)},
                           {"frame_count", scene.frameCount},
                           {"update_to_frame", orNull(scene.movedFrame)},
                           {"triangles", scene.scene.triangleCount()},
                           {"valid_triangles", scene.scene.primitives().validTriangles().size()},
                           {"spheres_and_cones_left_out", scene.scene.spheres.size() + scene.scene.cones.size()}};
    json.update(sceneFileJson(scene.scene));
    return json;
}

}  // namespace bvhlab::check
