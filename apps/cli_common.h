// What every subcommand shares: --env files, -D overrides, loading the scene and building
// the chosen accelerator with a report on stderr.
#pragma once

#include "framework/accelerator.h"
#include "framework/env.h"
#include "framework/scene.h"

#include <CLI/CLI.hpp>

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

// The scene from `file`, else from Scene::file (in Scene::dir), else the embedded default; load problems
// (degenerate triangles, unsupported NFF primitives, warnings) are reported on stderr.
Scene loadSceneFor(const std::string& file, const Env& env);

struct BuiltAccelerator {
    std::unique_ptr<Accelerator> accel;
    BuildStats stats;
};
BuiltAccelerator buildAccelerator(const Scene& scene, const Env& env);

// Runs `body`, turning InputError and other exceptions into a one-line message and exit code 1.
int runGuarded(const std::function<void()>& body);

}  // namespace bvhlab
