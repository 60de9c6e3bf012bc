#include "apps/runtime/child_job.h"

#include "apps/runtime/atomic_write.h"
#include "apps/runtime/progress.h"
#include "framework/core/fatal_signal_report.h"

#include <fmt/format.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <thread>
#include <vector>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace bvhlab {
namespace {

using Clock = std::chrono::steady_clock;

// This process's command line as it was given, argv[0] included.
std::vector<std::string> ownCommandLine() {
    std::ifstream in("/proc/self/cmdline", std::ios::binary);
    std::vector<std::string> words;
    for (std::string word; std::getline(in, word, '\0');) words.push_back(word);
    return words;
}

pid_t startProgram(const std::vector<std::string>& words) {
    std::vector<char*> argv;
    for (const std::string& word : words) argv.push_back(const_cast<char*>(word.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (const int error = posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, argv.data(), environ))
        throw std::runtime_error(fmt::format("cannot start a process for a job: {}", std::strerror(error)));
    return pid;
}

// Waits for the child; after `timeoutSeconds` (0: never) kills it. The child stays in this
// process group, so that Ctrl-C ends it with the parent; the threads it started die with it.
// Returns its wait status, and whether it was killed for its time.
std::pair<int, bool> waitFor(pid_t pid, double timeoutSeconds, Clock::time_point start) {
    int status = 0;
    auto pause = std::chrono::milliseconds(1);
    for (;;) {
        const pid_t done = waitpid(pid, &status, WNOHANG);
        if (done == pid) return {status, false};
        if (done < 0 && errno != EINTR)
            throw std::runtime_error(fmt::format("waiting for a job's process: {}", std::strerror(errno)));
        if (timeoutSeconds > 0 && std::chrono::duration<double>(Clock::now() - start).count() >= timeoutSeconds) {
            ::kill(pid, SIGKILL);
            while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            return {status, true};
        }
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, std::chrono::milliseconds(50));  // quick jobs end quickly
    }
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

// "2 s", "1.5 s": a time-out as the user gave it.
std::string formatSeconds(double seconds) { return fmt::format("{:g} s", seconds); }

}  // namespace

void ChildJob::run(const std::function<nlohmann::json()>& body) const {
    reportFatalSignalsTo(resultFile);
    nlohmann::json out;
    try {
        out = {{"result", body()}};
    } catch (const std::exception& e) {
        out = {{"error", e.what()}};
    }
    writeFileAtomically(resultFile, out.dump() + "\n");
}

void ChildJob::finish(const nlohmann::json& result) const {
    writeFileAtomically(resultFile, nlohmann::json{{"result", result}}.dump() + "\n");
    std::fflush(stdout);
    std::fflush(stderr);
    std::_Exit(0);
}

std::string JobOutcome::failure() const {
    if (reason == "threw") return detail;
    return detail.empty() ? reason : reason + ": " + detail;
}

JobOutcome runJobInChild(const std::string& job, double timeoutSeconds) {
    static std::atomic<int> jobsStarted{0};
    const std::filesystem::path resultFile =
        std::filesystem::temp_directory_path() / fmt::format("bvhlab-job-{}-{}.json", ::getpid(), jobsStarted++);
    std::vector<std::string> words = ownCommandLine();
    words.insert(words.end(), {kChildJobOption, job, kChildResultOption, resultFile.string()});
    const auto start = Clock::now();
    const auto [status, timedOut] = waitFor(startProgram(words), timeoutSeconds, start);
    const std::string text = readAndRemove(resultFile);
    JobOutcome outcome;
    outcome.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (timedOut) {
        outcome.reason = "timed out after " + formatSeconds(timeoutSeconds);
        Progress::endInterruptedLine();
        return outcome;
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        const nlohmann::json json = nlohmann::json::parse(text, nullptr, false);
        if (json.is_object() && json.contains("result")) {
            outcome.result = json["result"];
            return outcome;
        }
        if (json.is_object() && json.contains("error")) {
            outcome.reason = "threw";
            outcome.detail = json["error"].get<std::string>();
            return outcome;
        }
    }
    // A child that left its fatal-signal report crashed, whether it then died of the signal or a
    // handler installed before bvhlab's (a sanitizer's) ended it with an exit code.
    if (WIFSIGNALED(status) || !text.empty()) {
        outcome.reason = "crashed";
        outcome.detail = text.empty() ? "died of " + signalDescription(WTERMSIG(status)) : text;
        // Its live progress line, cut short, is not to run into the next line.
        Progress::endInterruptedLine();
    } else {
        outcome.reason = fmt::format("its process ended with exit code {} and no result", WEXITSTATUS(status));
    }
    return outcome;
}

}  // namespace bvhlab
