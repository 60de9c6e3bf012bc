// What fuzz_env does with an env once loaded, shared with its regression tests
// (tests/fuzz/test_fuzz_regressions.cpp): every registered key read back through its typed getter
// and through the consumers of the env (BVH and Embree configuration, camera, render settings).
#pragma once

#include "accel/bvh/bvh_env.h"
#include "accel/embree/embree_accelerator.h"
#include "framework/render/camera.h"
#include "framework/config/env.h"
#include "framework/render/renderer.h"

#include <nlohmann/json.hpp>

namespace bvhlab {

inline void readEveryEnvKey(const Env& env) {
    for (const auto& [name, key] : env.registry().keys()) {
        switch (key.type) {
        case EnvType::Bool: (void)env.getBool(name); break;
        case EnvType::Int: (void)env.getInt(name); break;
        case EnvType::Float: (void)env.getFloat(name); break;
        case EnvType::String:
        case EnvType::Choice: (void)env.getString(name); break;
        case EnvType::Path: (void)env.getPath(name); break;
        case EnvType::Vec3: (void)env.getVec3(name); break;
        case EnvType::Vec3List: (void)env.getVec3List(name); break;
        }
        (void)env.isExplicit(name);
    }
    (void)env.toJson();
    (void)bvhConfigFromEnv(env);
    (void)EmbreeConfig::fromEnv(env);
    Scene scene;
    scene.finalize();
    (void)RenderSettings::fromEnv(env, scene, resolveCamera(scene, env));
}

}  // namespace bvhlab
