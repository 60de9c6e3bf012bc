// libFuzzer target for the env parser: the input is loaded as an env file, each of its lines is
// also given as a -D override, and then every registered key is read back with its getter and
// through the consumers of the env (BVH and Embree configuration, camera, render settings).
// Bad input must end in an InputError; anything else is a finding. Built with -DBVHLAB_FUZZ=ON.
#include "accel/bvh/bvh_env.h"
#include "accel/embree/embree_accelerator.h"
#include "framework/camera.h"
#include "framework/env.h"
#include "framework/error.h"
#include "framework/renderer.h"

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace {

// Reads every key back through its typed getter.
void readEverything(const bvhlab::Env& env) {
    using bvhlab::EnvType;
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
    (void)bvhlab::bvhConfigFromEnv(env);
    (void)bvhlab::EmbreeConfig::fromEnv(env);
    bvhlab::Scene scene;
    scene.finalize();
    const bvhlab::CameraSpec camera = bvhlab::resolveCamera(scene, env);
    (void)bvhlab::RenderSettings::fromEnv(env, scene, camera);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // One scratch file per process, removed at exit.
    struct Scratch {
        std::string path = "/dev/shm/bvhlab-fuzz-env-" + std::to_string(getpid()) + ".env";
        ~Scratch() { std::remove(path.c_str()); }
    };
    static const Scratch scratch;
    const std::string& path = scratch.path;
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;

    bvhlab::Env env;
    try {
        env.loadFile(path);
    } catch (const bvhlab::InputError&) {
    }
    readEverything(env);

    bvhlab::Env overridden;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        try {
            overridden.setOverride(line);
        } catch (const bvhlab::InputError&) {
        }
    }
    readEverything(overridden);
    return 0;
}
