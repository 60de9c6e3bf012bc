// What every subcommand shares: --env files, -D overrides, loading the scene and building
// the chosen accelerator with a report on stderr.
#pragma once

#include "apps/common/progress.h"
#include "framework/config/env.h"
#include "framework/core/accelerator.h"
#include "framework/render/camera.h"
#include "framework/render/framebuffer.h"
#include "framework/render/renderer.h"
#include "framework/scene/scene.h"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace bvhlab {

// Every subcommand's configuration options. The layers, later ones winning: env/global.env
// (unless --no-global-env), a scene's env file (camera, lights), the --env files, --threads,
// then the -D overrides.
struct EnvOptions {
    std::vector<std::string> envFiles;
    std::vector<std::string> overrides;
    std::vector<std::string> plugins;  // --plugin
    // Accelerators a command names outside the env (--accel, parseAccelOption): their plugins
    // are found by name before the layers are checked, so env files and -D may set their keys.
    std::vector<std::string> accelerators;
    bool noGlobalEnv = false;
    int threads = -1;  // --threads; -1: not given

    // Adds --env, -D, --no-global-env and --plugin.
    void addTo(CLI::App& command);
    // Adds --threads N (0 = all hardware threads), setting SetRayTracing::threads.
    void addThreadsTo(CLI::App& command);
    // Loads the plugins first (--plugin, ASDS::plugins of the layers, ASDS::type's by name; see
    // apps/common/plugins.h), then the layers. Throws InputError.
    Env load(const std::filesystem::path& sceneEnvFile = {}) const;
    // The env files load() reads, in order.
    std::vector<std::string> files(const std::filesystem::path& sceneEnvFile = {}) const;

private:
    void loadPlugins(const std::vector<std::string>& layerFiles) const;
};

// The env file under env/scenes/ whose Scene::file is `sceneFile` (the same file on disk), or
// empty: so a scene named by its file is seen from its own camera with its own lights.
std::filesystem::path sceneEnvFor(const std::filesystem::path& sceneFile, const EnvOptions& options);

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

// How loadSceneFor got its scene.
struct SceneLoadInfo {
    bool fromCache = false;           // read from the scene cache, not parsed
    std::filesystem::path cacheFile;  // the cache entry read or written; empty when the cache was not used
    double ms = 0.0;                  // load time (hashing, reading or parsing, finalize)
};

// The scene of Scene::file (in Scene::dir; --scene sets it absolute), else the embedded default; load problems
// (degenerate primitives, NFF spheres and cones, warnings) are reported on stderr. With `useCache`
// a scene file is read from / stored into the binary cache in Scene::cacheDir (empty = no cache; see
// framework/scene/scene_cache.h); `bvhlab batch` uses it, render, raycast and bench parse every time.
Scene loadSceneFor(const Env& env, bool useCache = false, SceneLoadInfo* info = nullptr);

struct BuiltAccelerator {
    std::unique_ptr<Accelerator> accel;
    BuildStats stats;
};
BuiltAccelerator buildAccelerator(const Scene& scene, const Env& env);

// Renders with a progress line on `progress`: phase `label`, tiles done, rays per second.
RenderStats renderWithProgress(const Scene& scene, const Accelerator& accel, const Camera& camera,
                               const RenderSettings& settings, Framebuffer& fb, Progress& progress,
                               const std::string& label);

// An output path given to `option`, checked the same way by every subcommand: not empty, not a
// folder (for a file, or a path without extension); its folder is created. Throws InputError.
std::filesystem::path prepareOutputFile(const std::string& path, const std::string& option = "--out");
// An output folder given to `option`: not empty; created.
std::filesystem::path prepareOutputFolder(const std::string& path, const std::string& option = "--out");

// "a, b,,c" -> {"a", "b", "c"}: every option's comma-separated list.
std::vector<std::string> splitCommaList(const std::string& text);

// Writes `text` to `file` by way of a temporary file beside it, so a reader (or a run resumed
// after an interruption) never sees half a file.
void writeFileAtomically(const std::filesystem::path& file, const std::string& text);

// For a command line that CLI11 refused with a word left over: if that word is the value of a
// -D written without '=' (`-DASDS::type grid`), what to write instead; else empty.
std::string overrideWithoutEqualsHint(int argc, const char* const* argv);

// Runs `body`, turning InputError and other exceptions into a one-line message and exit code 1.
int runGuarded(const std::function<void()>& body);

}  // namespace bvhlab
