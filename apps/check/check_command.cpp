// `bvhlab check --accel NAME`: the conformance suite (apps/check/conformance.h) for one
// accelerator. One line per check on stdout (PASS/FAIL, counts, time) and the failures' rays
// under it; exit 0 when every check passes, 1 when one fails, 2 on bad input (an unknown
// accelerator or check, a bad env file or -D).
#include "accel/registry.h"
#include "apps/check/conformance.h"
#include "apps/common/accel_config.h"
#include "apps/common/cli_common.h"
#include "apps/common/commands.h"
#include "apps/common/progress.h"
#include "framework/core/error.h"
#include "framework/report/provenance.h"

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace bvhlab {
namespace {

struct CheckCommandOptions {
    EnvOptions env;
    std::string accel;
    std::string checks;  // empty: all
    std::string json;
};

std::string resultLine(const check::CheckResult& r) {
    const char* verdict = r.skipped ? "SKIP" : (r.passed() ? "PASS" : "FAIL");
    std::string line = fmt::format("{} {:<21} {:>3} scenes {:>8} {:<6} {:>6} failures {:>7.1f} s", verdict, r.check,
                                   r.scenes, r.cases, r.unit, r.failures, r.seconds);
    if (!r.note.empty()) line += "  (" + r.note + ")";
    return line;
}

nlohmann::json resultJson(const check::CheckResult& r) {
    return {{"check", r.check},   {"passed", r.passed()}, {"skipped", r.skipped}, {"scenes", r.scenes},
            {"cases", r.cases},   {"unit", r.unit},       {"failures", r.failures}, {"seconds", r.seconds},
            {"note", r.note},     {"examples", r.examples}};
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
    std::vector<std::string> names = options.checks.empty() ? check::checkNames() : splitCommaList(options.checks);
    if (names.empty()) throw InputError(fmt::format("--checks: none given (known: {})", fmt::join(check::checkNames(), ", ")));
    for (const std::string& name : names) check::findCheck(name);
    const std::filesystem::path json = options.json.empty() ? std::filesystem::path() : prepareOutputFile(options.json, "--json");

    const check::Subject subject{options.accel, [&] { return createAccelerator(config.name, env); }};
    Progress progress;
    check::CheckOptions checkOptions;
    uint64_t lastDone = 0;
    checkOptions.progress = [&](uint64_t done, uint64_t /*total*/) {
        if (done > lastDone) progress.advance(done - lastDone);
        lastDone = done;
    };
    bool failed = false;
    nlohmann::json results = nlohmann::json::array();
    for (const std::string& name : names) {
        lastDone = 0;
        progress.phase(fmt::format("check {}: {}", options.accel, name));
        const check::CheckResult r = check::runCheck(name, subject, checkOptions);
        progress.finish();
        fmt::print("{}\n", resultLine(r));
        for (const std::string& e : r.examples) fmt::print("    {}\n", e);
        std::fflush(stdout);
        failed |= !r.passed();
        results.push_back(resultJson(r));
    }
    fmt::print("check {}: {}\n", options.accel, failed ? "FAILED" : "all checks passed");
    if (!json.empty()) {
        const nlohmann::json out = {{"accel", options.accel},
                                    {"passed", !failed},
                                    {"checks", results},
                                    {"env", env.toJson()},
                                    {"provenance", provenanceJson()}};
        writeFileAtomically(json, out.dump(2) + "\n");
    }
    return failed ? 1 : 0;
}

}  // namespace

void addCheckCommand(CLI::App& app) {
    auto options = std::make_shared<CheckCommandOptions>();
    CLI::App* command = app.add_subcommand(
        "check", "the conformance suite for one accelerator: agreement with a double-precision reference, any-hit, batch, "
                 "mixed primitives, degenerate triangles, watertightness, builds at the edge (docs/accuracy.md)");
    options->env.addTo(*command);
    command->add_option("--accel", options->accel,
                        "the accelerator to check, NAME or NAME:Key=value:... (`bvhlab keys` lists them)")
        ->required();
    command->add_option("--checks", options->checks,
                        fmt::format("comma-separated checks to run (default: all of {})", fmt::join(check::checkNames(), ",")));
    command->add_option("--json", options->json, "write the results as JSON to this file");
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
