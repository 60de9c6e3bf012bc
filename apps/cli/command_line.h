// What every subcommand's command line shares: the env options (--env, -D, --no-global-env,
// --plugin, --threads), the hint for a -D written without '=', and a failed run's exit code.
#pragma once

#include "apps/runtime/child_job.h"
#include "apps/runtime/env_options.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace bvhlab {

// Adds --env, -D, --no-global-env and --plugin, filling `options`.
void addEnvOptions(CLI::App& command, EnvOptions& options);
// Adds --threads N (0 = all hardware threads), setting SetRayTracing::threads.
void addThreadsOption(CLI::App& command, EnvOptions& options);
// Adds --scenes as batch, bench, tradeoff and stress take it (expandSceneList, apps/runtime/
// scene_list.h): repeatable, each a comma-separated list. `others` names what else this command
// takes, `byDefault` what it goes over without one.
void addScenesOption(CLI::App& command, std::vector<std::string>& scenes, const std::string& others,
                     const std::string& byDefault);

// Adds the hidden options that make the program a child running one job (apps/runtime/child_job.h).
void addChildJobOptions(CLI::App& command, ChildJob& job);
// Adds --job-timeout SECONDS (0 = none): how long one job may run before it is killed and fails.
// The default, half an hour, is far above a job of the shipped scenes (minutes at most) and ends
// a build or a trace that never returns before the night is lost.
inline constexpr double kDefaultJobTimeoutSeconds = 1800;
void addJobTimeoutOption(CLI::App& command, double& seconds);

// For a command line that CLI11 refused with a word left over: if that word is the value of a
// -D written without '=' (`-DASDS::type grid`), what to write instead; else empty.
std::string overrideWithoutEqualsHint(int argc, const char* const* argv);

// Runs `body`, turning InputError and other exceptions into a one-line message and exit code 1.
int runGuarded(const std::function<void()>& body);

// The exit code of a run whose jobs ran to the end but some failed (crashed, threw, timed out):
// their count is on stderr and in the command's JSON.
inline constexpr int kSomeJobsFailedExitCode = 3;

// A command's callback around `run`, which returns how many of its jobs failed: an exception
// ends it with runGuarded's exit code, failed jobs with kSomeJobsFailedExitCode.
void runJobsGuarded(const std::function<size_t()>& run);

}  // namespace bvhlab
