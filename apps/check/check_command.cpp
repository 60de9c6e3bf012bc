// `bvhlab check --accel NAME [--scene FILE]`: the conformance suite (accel/verify/conformance.h)
// for one accelerator, on the user's scenes too, each check in a child process
// (apps/check/check_process.h) unless --in-process.
// One line per check on stdout (PASS/WARN/FAIL/SKIP, counts, time) and the failures' rays under
// it; exit 0 when every check passes (a warning included), 1 when one fails (a crash, an exception
// or a time-out, --job-timeout, included), 2 on bad input (an unknown accelerator or check, a bad
// env file or -D, a scene file missing or malformed).
#include "accel/registry.h"
#include "accel/verify/conformance.h"
#include "apps/check/check_process.h"
#include "apps/check/check_scenes.h"
#include "apps/cli/command_line.h"
#include "apps/cli/commands.h"
#include "apps/runtime/accel_config.h"
#include "apps/runtime/atomic_write.h"
#include "apps/runtime/comma_list.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/progress.h"
#include "apps/runtime/run_record.h"
#include "framework/config/common_keys.h"
#include "framework/core/error.h"
#include "framework/report/provenance.h"

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

namespace bvhlab {
namespace {

struct CheckCommandOptions {
    EnvOptions env;
    std::string accel;
    std::string checks;               // empty: all
    std::vector<std::string> scenes;  // --scene, as given
    std::string json;
    bool inProcess = false;
    double timeoutSeconds = 0;
    ChildJob child;
};

std::string resultLine(const verify::CheckResult& r) {
    const char* verdict = r.skipped ? "SKIP" : !r.passed() ? "FAIL" : r.warning ? "WARN" : "PASS";
    std::string line = fmt::format("{} {:<21} {:>3} scenes {:>8} {:<6} {:>6} failures {:>7.1f} s", verdict, r.check,
                                   r.scenes, r.cases, r.unit, r.failures, r.seconds);
    if (!r.note.empty()) line += "  (" + r.note + ")";
    return line;
}

// Runs a check here on `threads` (0: all hardware threads), its progress on stderr. A check that
// throws (a plugin's exception, which the guard names) fails with the message as its example.
verify::CheckResult runCheckHere(const std::string& name, const verify::Subject& subject, int threads,
                                 const std::vector<std::shared_ptr<const check::CheckScene>>& scenes) {
    Progress progress;
    progress.phase(fmt::format("check {}: {}", subject.name, name));
    verify::CheckOptions options;
    options.threads = threads;
    options.scenes = check::userScenes(scenes);
    uint64_t lastDone = 0;
    options.progress = [&](uint64_t done, uint64_t /*total*/) {
        if (done > lastDone) progress.advance(done - lastDone);
        lastDone = done;
    };
    try {
        return verify::runCheck(name, subject, options);
    } catch (const std::exception& e) {
        verify::CheckResult failed;
        failed.check = name;
        failed.failures = 1;
        failed.note = "threw";
        failed.examples.push_back(fmt::format("{}: {}", name, e.what()));
        return failed;
    }
}

// Returns the exit code: 0 all passed, 1 a check failed.
int runChecks(CheckCommandOptions options) {
    const std::vector<AccelConfig> configs = parseAccelConfigList(options.accel);
    if (configs.size() != 1)
        throw InputError(fmt::format("--accel {}: give one accelerator, NAME or NAME:Key=value:...", options.accel));
    const AccelConfig& config = configs.front();
    nameAccelerators(configs, options.env);
    const Env base = options.env.load();
    checkAccelConfigs(configs, base);  // an unknown name or key fails before any work
    const Env env = accelConfigEnv(config, base);
    createAccelerator(config.name, env);
    std::vector<std::string> names = options.checks.empty() ? verify::checkNames() : splitCommaList(options.checks);
    if (names.empty())
        throw InputError(fmt::format("--checks: none given (known: {})", fmt::join(verify::checkNames(), ", ")));
    for (const std::string& name : names) verify::findCheck(name);
    // Named as registered: the checks look up what the structure promises by name.
    const verify::Subject subject{config.name, [&] { return createAccelerator(config.name, env); }};
    const int threads = env.get(keys::SetRayTracing::threads);
    // Read here before any check runs (a scene missing or malformed is bad input), and again in
    // each child whose check takes scenes.
    const bool readScenes = !options.child.isChild() || verify::findCheck(options.child.job).takesScenes;
    const auto scenes = readScenes ? check::readCheckScenes(options.scenes, options.env)
                                   : std::vector<std::shared_ptr<const check::CheckScene>>();
    if (options.child.isChild()) {
        options.child.run([&] { return check::toJson(runCheckHere(options.child.job, subject, threads, scenes)); });
        return 0;
    }
    const std::filesystem::path json =
        options.json.empty() ? std::filesystem::path() : prepareOutputFile(options.json, "--json");

    bool failed = false;
    std::vector<std::string> warned;
    nlohmann::json results = nlohmann::json::array();
    for (const std::string& name : names) {
        const verify::CheckResult r = options.inProcess ? runCheckHere(name, subject, threads, scenes)
                                                        : check::runCheckInChild(name, options.timeoutSeconds);
        fmt::print("{}\n", resultLine(r));
        for (const std::string& e : r.examples) fmt::print("    {}\n", e);
        std::fflush(stdout);
        failed |= !r.passed();
        if (r.passed() && r.warning) warned.push_back(name);
        results.push_back(check::toJson(r));
    }
    const std::string warnings = warned.empty() ? "" : fmt::format(", with a warning ({})", fmt::join(warned, ", "));
    fmt::print("check {}: {}\n", options.accel, failed ? "FAILED" : "all checks passed" + warnings);
    if (!json.empty()) {
        nlohmann::json sceneList = nlohmann::json::array();
        for (const auto& scene : scenes) sceneList.push_back(check::toJson(*scene));
        const nlohmann::json out = {{"accel", options.accel}, {"passed", !failed},   {"scenes", sceneList},
                                    {"checks", results},      {"env", env.toJson()}, {"provenance", provenanceJson()},
                                    {"run", runJson()}};
        writeFileAtomically(json, out.dump(2) + "\n");
    }
    return failed ? 1 : 0;
}

std::vector<std::string> sceneTakingChecks() {
    std::vector<std::string> names;
    for (const verify::CheckInfo& c : verify::conformanceChecks())
        if (c.takesScenes) names.push_back(c.name);
    return names;
}

}  // namespace

void addCheckCommand(CLI::App& app) {
    auto options = std::make_shared<CheckCommandOptions>();
    CLI::App* command = app.add_subcommand(
        "check",
        "the conformance suite for one accelerator: agreement with a double-precision reference, any-hit, batch, "
        "mixed primitives, degenerate triangles, watertightness, builds at the edge, updates, cost against sahbvh "
        "(docs/accuracy.md)");
    addEnvOptions(*command, options->env);
    addThreadsOption(*command, options->env);
    command
        ->add_option("--accel", options->accel,
                     "the accelerator to check, NAME or NAME:Key=value:... (`bvhlab keys` lists them)")
        ->required();
    command->add_option(
        "--checks", options->checks,
        fmt::format("comma-separated checks to run (default: all of {})", fmt::join(verify::checkNames(), ",")));
    command->add_option(
        "--scene", options->scenes,
        fmt::format("a scene to check beside the generated ones in the checks that take scenes ({}): a scene file "
                    "(here or in Scene::dir; an animated .aff at Scene::frame), a scene env file, a .list file or a "
                    "scene's name; repeatable or comma-separated",
                    fmt::join(sceneTakingChecks(), ",")));
    command->add_option("--json", options->json, "write the results as JSON to this file");
    command->add_flag("--in-process", options->inProcess,
                      "run the checks in this process, not each in a child process: a crash ends the run "
                      "(for a debugger)");
    addJobTimeoutOption(*command, options->timeoutSeconds);
    addChildJobOptions(*command, options->child);
    command->callback([options] {
        int result = 0;
        bool badInput = false;
        const int code = runGuarded([&] {
            try {
                result = runChecks(*options);
            } catch (const InputError& e) {
                fmt::print(stderr, "error: {}\n", e.what());
                badInput = true;
            }
        });
        if (badInput) throw CLI::RuntimeError(2);
        if (code != 0) throw CLI::RuntimeError(code);
        if (result != 0) throw CLI::RuntimeError(result);
    });
}

}  // namespace bvhlab
