// The layers a run's env is made of, as every front end gives them (the command line's --env,
// -D, --plugin, --threads; the Python module's env dicts).
#pragma once

#include "framework/config/env.h"

#include <filesystem>
#include <string>
#include <vector>

namespace bvhlab {

// The layers, later ones winning: env/global.env (unless noGlobalEnv), a scene's env file
// (camera, lights), the envFiles, threads, then the overrides.
struct EnvOptions {
    std::vector<std::string> envFiles;
    std::vector<std::string> overrides;  // Section::key=value
    std::vector<std::string> plugins;    // plugin files, loaded first
    // Accelerators a command names outside the env (--accel, nameAccelerators): their plugins
    // are found by name before the layers are checked, so env files and overrides may set their keys.
    std::vector<std::string> accelerators;
    bool noGlobalEnv = false;
    int threads = -1;  // SetRayTracing::threads; -1: not given

    // Loads the plugins first (plugins, ASDS::plugins of the layers, ASDS::type's by name; see
    // apps/runtime/plugins.h), then the layers. Throws InputError.
    Env load(const std::filesystem::path& sceneEnvFile = {}) const;
    // The env files load() reads, in order.
    std::vector<std::string> files(const std::filesystem::path& sceneEnvFile = {}) const;

private:
    void loadPlugins(const std::vector<std::string>& layerFiles) const;
};

}  // namespace bvhlab
