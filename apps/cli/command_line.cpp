#include "apps/cli/command_line.h"

#include "framework/core/error.h"

#include <fmt/core.h>

#include <string_view>

namespace bvhlab {

void addEnvOptions(CLI::App& command, EnvOptions& options) {
    command.add_option("--env", options.envFiles,
                       "env file(s) layered on env/global.env (and the scene's env file), later ones win");
    command
        .add_option("-D", options.overrides, "override an env key: -DSection::key=value (repeatable; wins over files)")
        ->allow_extra_args(false);
    command.add_flag("--no-global-env", options.noGlobalEnv,
                     "do not read env/global.env: start from the keys' defaults");
    command.add_option("--plugin", options.plugins,
                       "load a plugin's accelerators from this file (repeatable; docs/plugins.md)");
}

void addThreadsOption(CLI::App& command, EnvOptions& options) {
    command.add_option("--threads", options.threads, "threads (SetRayTracing::threads); 0 = all hardware threads")
        ->check(CLI::Range(0, 1024));
}

void addChildJobOptions(CLI::App& command, ChildJob& job) {
    // An empty group hides them from --help: they are runJobInChild's, not a user's.
    command.add_option(kChildJobOption, job.job, "run this job alone, as a child process")->group("");
    command.add_option(kChildResultOption, job.resultFile, "the file for the child's result")->group("");
}

void addJobTimeoutOption(CLI::App& command, double& seconds) {
    seconds = kDefaultJobTimeoutSeconds;
    command
        .add_option("--job-timeout", seconds, "seconds each job may run before it is killed and fails; 0 = no limit")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1e9));
}

void addScenesOption(CLI::App& command, std::vector<std::string>& scenes, const std::string& others,
                     const std::string& byDefault) {
    command.add_option("--scenes", scenes,
                       others +
                           "scene env files, .list files, scene files (here or in Scene::dir) or scenes' names "
                           "(teapots for env/scenes/teapots.env); repeatable or comma-separated (default: " +
                           byDefault + ")");
}

std::string overrideWithoutEqualsHint(int argc, const char* const* argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (!arg.starts_with("-D") || arg.starts_with("--")) continue;
        // -DKey or -D Key, then a word that is not an option.
        const int keyAt = arg == "-D" ? i + 1 : i;
        if (keyAt + 1 >= argc) continue;
        const std::string_view key = arg == "-D" ? std::string_view(argv[keyAt]) : arg.substr(2);
        const std::string_view value = argv[keyAt + 1];
        if (key.find('=') != std::string_view::npos || value.starts_with('-')) continue;
        return fmt::format("-D{} {}: -D takes Section::key=value as one word; write -D{}={}", key, value, key, value);
    }
    return {};
}

int runGuarded(const std::function<void()>& body) {
    try {
        body();
        return 0;
    } catch (const InputError& e) {
        fmt::print(stderr, "error: {}\n", e.what());
    } catch (const std::exception& e) {
        fmt::print(stderr, "error: {}\n", e.what());
    }
    return 1;
}

void runJobsGuarded(const std::function<size_t()>& run) {
    size_t failed = 0;
    const int code = runGuarded([&] { failed = run(); });
    if (code != 0) throw CLI::RuntimeError(code);
    if (failed) throw CLI::RuntimeError(kSomeJobsFailedExitCode);
}

}  // namespace bvhlab
