#include "apps/check/check_process.h"

#include "apps/runtime/atomic_write.h"
#include "apps/runtime/progress.h"
#include "framework/core/fatal_signal_report.h"

#include <fmt/format.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace bvhlab::check {
namespace {

// This process's command line as it was given, argv[0] included.
std::vector<std::string> ownCommandLine() {
    std::ifstream in("/proc/self/cmdline", std::ios::binary);
    std::vector<std::string> words;
    for (std::string word; std::getline(in, word, '\0');) words.push_back(word);
    return words;
}

// Runs this program with `words` as its argv and returns its wait status.
int runProgram(const std::vector<std::string>& words) {
    std::vector<char*> argv;
    for (const std::string& word : words) argv.push_back(const_cast<char*>(word.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (const int error = posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, argv.data(), environ))
        throw std::runtime_error(fmt::format("cannot start a process for a check: {}", std::strerror(error)));
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) throw std::runtime_error(fmt::format("waiting for a check's process: {}", std::strerror(errno)));
    return status;
}

std::string readAndRemove(const std::filesystem::path& file) {
    std::string text;
    {
        std::ifstream in(file, std::ios::binary);
        text.assign(std::istreambuf_iterator<char>(in), {});
    }
    std::error_code ec;
    std::filesystem::remove(file, ec);
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    return text;
}

}  // namespace

void ChildCheck::reportFatalSignals() const { reportFatalSignalsTo(resultFile); }

void ChildCheck::writeResult(const verify::CheckResult& result) const { writeFileAtomically(resultFile, toJson(result).dump() + "\n"); }

verify::CheckResult runCheckInChild(const std::string& name) {
    const std::filesystem::path resultFile =
        std::filesystem::temp_directory_path() / fmt::format("bvhlab-check-{}-{}.json", ::getpid(), name);
    std::vector<std::string> words = ownCommandLine();
    words.insert(words.end(), {"--child-check", name, "--child-result", resultFile.string()});
    const auto start = std::chrono::steady_clock::now();
    const int status = runProgram(words);
    const std::string text = readAndRemove(resultFile);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        const nlohmann::json json = nlohmann::json::parse(text, nullptr, false);
        if (!json.is_discarded()) return checkResultFromJson(json);
    }
    verify::CheckResult failed;
    failed.check = name;
    failed.failures = 1;
    failed.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // A child that left its fatal-signal report crashed, whether it then died of the signal or a
    // handler installed before bvhlab's (a sanitizer's) ended it with an exit code.
    if (WIFSIGNALED(status) || !text.empty()) {
        // The child's report: the signal, and the plugin call with its ray or primitive count.
        failed.note = "crashed";
        failed.examples.push_back(fmt::format("{}: {}", name, text.empty() ? "died of " + signalDescription(WTERMSIG(status)) : text));
        // Its live progress line, cut short, is not to run into the next line.
        Progress::endInterruptedLine();
    } else {
        failed.note = fmt::format("its process ended with exit code {} and no result", WEXITSTATUS(status));
    }
    return failed;
}

nlohmann::json toJson(const verify::CheckResult& r) {
    return {{"check", r.check},   {"passed", r.passed()}, {"skipped", r.skipped},   {"warning", r.warning},
            {"scenes", r.scenes}, {"cases", r.cases},     {"unit", r.unit},         {"failures", r.failures},
            {"seconds", r.seconds}, {"note", r.note},     {"examples", r.examples}};
}

verify::CheckResult checkResultFromJson(const nlohmann::json& json) {
    verify::CheckResult r;
    r.check = json.at("check");
    r.unit = json.at("unit");
    r.scenes = json.at("scenes");
    r.cases = json.at("cases");
    r.failures = json.at("failures");
    r.skipped = json.at("skipped");
    r.warning = json.at("warning");
    r.note = json.at("note");
    r.examples = json.at("examples").get<std::vector<std::string>>();
    r.seconds = json.at("seconds");
    return r;
}

}  // namespace bvhlab::check
