// What every subcommand shares: --env files, -D overrides, loading the scene and building
// the chosen accelerator with a report on stderr.
#pragma once

#include "framework/accelerator.h"
#include "framework/env.h"
#include "framework/scene.h"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace bvhlab {

struct EnvOptions {
    std::vector<std::string> envFiles;
    std::vector<std::string> overrides;

    // Adds --env (repeatable, later files win) and -DSection::key=value (repeatable, wins over files).
    void addTo(CLI::App& command);
    // Loads env/global.env (or the --env files), then `extraFiles` (e.g. a scene's env file),
    // then applies the -D overrides.
    Env load(const std::vector<std::string>& extraFiles = {}) const;
};

// How loadSceneFor got its scene.
struct SceneLoadInfo {
    bool fromCache = false;           // read from the scene cache, not parsed
    std::filesystem::path cacheFile;  // the cache entry read or written; empty when the cache was not used
    double ms = 0.0;                  // load time (hashing, reading or parsing, finalize)
};

// The scene from `file`, else from Scene::file (in Scene::dir), else the embedded default; load problems
// (degenerate triangles, unsupported NFF primitives, warnings) are reported on stderr. With `useCache`
// a scene file is read from / stored into the binary cache in Scene::cacheDir (empty = no cache; see
// framework/scene_cache.h); `bvhlab batch` uses it, render, raycast and bench parse every time.
Scene loadSceneFor(const std::string& file, const Env& env, bool useCache = false, SceneLoadInfo* info = nullptr);

struct BuiltAccelerator {
    std::unique_ptr<Accelerator> accel;
    BuildStats stats;
};
BuiltAccelerator buildAccelerator(const Scene& scene, const Env& env);

// Writes `text` to `file` by way of a temporary file beside it, so a reader (or a run resumed
// after an interruption) never sees half a file.
void writeFileAtomically(const std::filesystem::path& file, const std::string& text);

// Runs `body`, turning InputError and other exceptions into a one-line message and exit code 1.
int runGuarded(const std::function<void()>& body);

}  // namespace bvhlab
