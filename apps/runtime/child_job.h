// One job of a command (a check, a batch's scene x accelerator, a bench's scene) run in a
// process of its own, so that a structure that crashes, throws or never returns fails that job
// alone, with the reason, and the command goes on with the next. The child is the program again
// (/proc/self/exe, never a fork of a process with running threads) with the parent's command line
// and two hidden options: the job to run and the file for its result (JSON), where its
// fatal-signal report goes too (framework/core/fatal_signal_report.h). The parent waits at most
// the job's time-out, then kills it.
#pragma once

#include <nlohmann/json.hpp>

#include <functional>
#include <string>

namespace bvhlab {

// The hidden options that make the program a child running one job (ChildJob's fields).
inline constexpr const char* kChildJobOption = "--child-job";
inline constexpr const char* kChildResultOption = "--child-result";

// What a child process is asked: one job, and where its result goes. Empty in the parent.
struct ChildJob {
    std::string job;
    std::string resultFile;

    bool isChild() const { return !job.empty(); }
    // Runs `body` as the child: its fatal signals reported in the result file, then its result,
    // or the message of the exception it threw, written there.
    void run(const std::function<nlohmann::json()>& body) const;
    // Writes `result` as the job's and ends the process at once: for a job whose own deadline
    // passed while a call that cannot be stopped (a build) still runs on another thread.
    [[noreturn]] void finish(const nlohmann::json& result) const;
};

// How a job run in a child ended: its result, or why there is none.
struct JobOutcome {
    nlohmann::json result;  // what the child's body returned; null when the job failed
    // Empty when the job passed, else "crashed", "threw", "timed out after 2 s" or "its process
    // ended with exit code 1 and no result".
    std::string reason;
    // The crash's report ("SIGSEGV (Segmentation fault) in plugin FILE, accelerator 'NAME':
    // build() of 12 primitives") or the exception's message; empty for the others.
    std::string detail;
    double seconds = 0;

    bool passed() const { return reason.empty(); }
    // What a table says of a failed job: "crashed: SIGSEGV ...", "timed out after 2 s", or
    // the exception's message alone.
    std::string failure() const;
};

// Runs `job` in a child process (this program with this command line and the hidden options)
// and waits for it at most `timeoutSeconds` (0: without end), killing it then. No file is left.
JobOutcome runJobInChild(const std::string& job, double timeoutSeconds);

}  // namespace bvhlab
