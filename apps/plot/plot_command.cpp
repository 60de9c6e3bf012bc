// `bvhlab plot PATH [--out DIR]`: draws the plots of a bench, tradeoff, tradeoff --builders,
// batch or animate output. Which one PATH is, is read from what it holds; the plot script of that
// output (apps/plot/*.py, installed as PREFIX/share/bvhlab/apps/plot) runs under Debian's
// /usr/bin/python3 with its matplotlib, which a python3 earlier on PATH may not see.
#include "apps/cli/command_line.h"
#include "apps/cli/commands.h"
#include "framework/config/install_paths.h"
#include "framework/core/error.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace bvhlab {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPython = "/usr/bin/python3";

// The plot script of the output at `path`: a bench or animate JSON file, or a folder holding the
// files that animate, tradeoff, tradeoff --builders or batch write.
std::string plotScriptFor(const fs::path& path) {
    if (fs::is_directory(path)) {
        for (const auto& [file, script] :
             {std::pair{"animate.json", "plot_animate.py"}, std::pair{"tradeoff.csv", "plot_tradeoff.py"},
              std::pair{"builders.csv", "plot_builders.py"}, std::pair{"results.csv", "plot_batch.py"}})
            if (fs::is_regular_file(path / file)) return script;
        throw inputError(path, 0,
                         "holds no output that bvhlab plot draws: no tradeoff.csv (tradeoff), builders.csv "
                         "(tradeoff --builders), results.csv (batch) or animate.json (animate); a bench's output "
                         "is its JSON file");
    }
    if (!fs::is_regular_file(path)) throw inputError(path, 0, "no such file or folder");
    std::ifstream in(path);
    const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
    if (!json.is_discarded() && json.is_object() && json.contains("contenders") && json.contains("frames"))
        return "plot_animate.py";
    if (json.is_discarded() || !json.is_object() || !json.contains("rows") || !json.contains("passes"))
        throw inputError(path, 0, "is not the JSON file of bvhlab bench or animate, nor a folder of tradeoff or batch");
    return "plot_bench.py";
}

// Runs `words` (words[0] the program) and returns its exit status; its output is this process's,
// or nothing when `silent`.
int runProcess(const std::vector<std::string>& words, bool silent) {
    std::vector<char*> argv;
    for (const std::string& word : words) argv.push_back(const_cast<char*>(word.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (silent) {
        posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    }
    pid_t pid = 0;
    const int error = posix_spawn(&pid, words[0].c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (error) throw InputError(fmt::format("cannot run {}: {}", words[0], std::strerror(error)));
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) throw InputError(fmt::format("waiting for {}: {}", words[0], std::strerror(errno)));
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

void addPlotCommand(CLI::App& app) {
    struct Options {
        std::string path, out;
    };
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand(
        "plot",
        "draw the plots of a bench or animate JSON file or a tradeoff, tradeoff --builders, batch or animate "
        "folder (PNG files; Debian's /usr/bin/python3 with python3-matplotlib)");
    command
        ->add_option("path", options->path,
                     "bench's or animate's JSON file, or the --out folder of tradeoff, tradeoff --builders, batch "
                     "or animate")
        ->required();
    command->add_option(
        "--out", options->out,
        "folder of the PNG files (default: PATH/plots for a folder, the JSON file's folder for a file)");
    command->callback([options] {
        const int code = runGuarded([&] {
            const fs::path script = dataFile("apps/plot") / plotScriptFor(options->path);
            if (access(kPython, X_OK) != 0)
                throw InputError(
                    fmt::format("bvhlab plot runs {}, which is missing: install Debian's "
                                "python3-matplotlib (apt-get install python3-matplotlib)",
                                kPython));
            if (runProcess({kPython, "-c", "import matplotlib"}, true) != 0)
                throw InputError(
                    fmt::format("bvhlab plot needs matplotlib for {}, which cannot import it: install "
                                "Debian's python3-matplotlib (apt-get install python3-matplotlib)",
                                kPython));
            std::vector<std::string> words = {kPython, script.string(), "--data", options->path};
            if (!options->out.empty()) words.insert(words.end(), {"--out", options->out});
            if (const int status = runProcess(words, false); status != 0)
                throw InputError(
                    fmt::format("{} failed (exit status {}) on {}", script.string(), status, options->path));
        });
        if (code != 0) throw CLI::RuntimeError(code);
    });
}

}  // namespace bvhlab
