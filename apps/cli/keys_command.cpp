// `bvhlab keys`: prints every env key and accelerator as Markdown (docs/env-keys.md), the plugins
// of the plugin folders' included, with the value env/global.env gives it; with --env, -D or
// --no-global-env, the configuration they resolve to instead: every key, its value, where the
// value came from and its default.
#include "accel/registry.h"
#include "apps/cli/command_line.h"
#include "apps/cli/commands.h"
#include "apps/runtime/plugins.h"
#include "apps/runtime/program_keys.h"

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

namespace bvhlab {

void addKeysCommand(CLI::App& app) {
    auto options = std::make_shared<EnvOptions>();
    CLI::App* command = app.add_subcommand(
        "keys",
        "print every env key and accelerator as Markdown (docs/env-keys.md); with --env or -D, the resolved values");
    addEnvOptions(*command, *options);
    command->callback([options, command] {
        const bool resolve = command->count("--env") + command->count("-D") + command->count("--no-global-env") > 0;
        const int code = runGuarded([&] {
            const Env env = options->load();
            loadPluginsOfFolders();  // listed as the commands would find them by name
            if (!resolve) {
                fmt::print("{}", envKeysMarkdown(env));
                return;
            }
            fmt::print("# env files: {}\n", fmt::join(options->files(), " "));
            const nlohmann::json resolved = env.toJson();
            for (const auto& [name, value] : resolved.items()) {
                const std::string from = value["from"].get<std::string>();
                const std::string& declared = env.registry().find(name)->defaultValue;
                fmt::print("{} {}  # {}\n", name, value["value"].get<std::string>(),
                           from == "default"
                               ? from
                               : fmt::format("{} (default: {})", from, declared.empty() ? "empty" : declared));
            }
        });
        if (code != 0) throw CLI::RuntimeError(code);
    });
}

}  // namespace bvhlab
