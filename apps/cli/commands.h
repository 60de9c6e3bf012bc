// One function per subcommand, each in its own file, adding itself to the program; a new
// subcommand is its file and its two lines here.
#pragma once

#include <CLI/CLI.hpp>

namespace bvhlab {

void addRenderCommand(CLI::App& app);
void addRaycastCommand(CLI::App& app);
void addRaysCommand(CLI::App& app);
void addKeysCommand(CLI::App& app);
void addPlotCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addBatchCommand(CLI::App& app);
void addStressCommand(CLI::App& app);
void addTradeoffCommand(CLI::App& app);
void addSpdCommand(CLI::App& app);
void addCheckCommand(CLI::App& app);
void addAnimateCommand(CLI::App& app);

// In the order `bvhlab --help` lists them.
inline constexpr void (*kCommands[])(CLI::App&) = {
    addRenderCommand,   addRaycastCommand, addRaysCommand,    addBenchCommand, addBatchCommand, addStressCommand,
    addTradeoffCommand, addSpdCommand,     addAnimateCommand, addCheckCommand, addKeysCommand,  addPlotCommand,
};

}  // namespace bvhlab
