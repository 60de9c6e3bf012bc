// What fuzz_env does with an env once loaded, shared with its regression tests
// (tests/fuzz/test_fuzz_regressions.cpp): every registered key read back through its typed getter
// and through the consumers of the env (BVH and Embree configuration, camera, render settings).
#pragma once

#include "accel/bvh/bvh_env.h"
#include "accel/embree/embree_accelerator.h"
#include "framework/config/env.h"
#include "framework/render/camera.h"
#include "framework/render/renderer.h"

#include <nlohmann/json.hpp>

namespace bvhlab {

inline void readEveryEnvKey(const Env& env) {
    for (const auto& [name, key] : env.registry().keys()) {
        // A handle made from the registered name reads like a declared key.
        switch (key.type) {
            case KeyType::Bool:
                (void)env.get(BoolKey(name, "", ""));
                break;
            case KeyType::Int:
                (void)env.get(IntKey(name, "", 0, 0, ""));
                break;
            case KeyType::Float:
                (void)env.get(FloatKey(name, "", 0, 0, ""));
                break;
            case KeyType::String:
                (void)env.get(TextKey(name, "", ""));
                break;
            case KeyType::Choice:
                (void)env.get(ChoiceKey(name, "", {}, ""));
                break;
            case KeyType::Path:
                (void)env.get(PathKey(name, "", ""));
                break;
            case KeyType::Vec3:
                (void)env.get(Vec3Key(name, "", ""));
                break;
            case KeyType::Vec3List:
                (void)env.get(Vec3ListKey(name, "", ""));
                break;
        }
        (void)env.isExplicit(name);
    }
    (void)env.toJson();
    (void)bvhSettingsFromEnv(env);
    (void)EmbreeConfig::fromEnv(env);
    Scene scene;
    scene.finalize();
    (void)RenderSettings::fromEnv(env, scene, resolveCamera(scene, env));
}

}  // namespace bvhlab
