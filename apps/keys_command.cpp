// `bvhlab keys`: prints every env key and accelerator as Markdown (docs/env-keys.md).
#include "accel/registry.h"
#include "apps/commands.h"

#include <fmt/core.h>

namespace bvhlab {

void addKeysCommand(CLI::App& app) {
    app.add_subcommand("keys", "print every env key and accelerator as Markdown (docs/env-keys.md)")
        ->callback([] { fmt::print("{}", envKeysMarkdown()); });
}

}  // namespace bvhlab
