// bvhlab: build, trace and measure bounding volume hierarchies.
#include "apps/cli/command_line.h"
#include "apps/cli/commands.h"
#include "apps/runtime/progress.h"
#include "apps/runtime/run_record.h"
#include "framework/core/fatal_signal_report.h"
#include "framework/report/provenance.h"

#include <fmt/core.h>

int main(int argc, char** argv) {
    // A crash inside a plugin names the plugin, the call and its ray before the process dies.
    bvhlab::installFatalSignalReport();
    bvhlab::recordRun(argc, argv);
    CLI::App app("bvhlab: a research ray tracer for building, measuring and comparing BVHs");
    app.set_version_flag("--version", std::string("bvhlab " BVHLAB_VERSION " (commit ") + bvhlab::gitCommit() + ")");
    // --quiet before or after the subcommand silences progress lines (results and errors stay).
    app.fallthrough();
    app.add_flag_callback(
        "--quiet", [] { bvhlab::Progress::setQuiet(true); }, "no progress lines on stderr");
    app.require_subcommand(1);
    for (auto addCommand : bvhlab::kCommands) addCommand(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // `-DKey value` leaves the value over, which CLI11 would call an unexpected argument.
        const std::string hint =
            dynamic_cast<const CLI::ExtrasError*>(&e) ? bvhlab::overrideWithoutEqualsHint(argc, argv) : "";
        if (hint.empty()) return app.exit(e);
        fmt::print(stderr, "error: {}\n", hint);
        return e.get_exit_code();
    }
    return 0;
}
