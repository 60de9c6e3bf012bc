// Runs the bvhlab program (test::bvhlabProgram()) with arguments, as the end-to-end tests do.
#pragma once

#include "tests/support/test_paths.h"

#include <sys/wait.h>
#include <cstdio>
#include <string>

namespace bvhlab::test {

struct Result {
    int exitCode;
    std::string output;  // stdout and stderr
};

// `sh -c COMMAND 2>&1`: its exit code and everything it printed.
inline Result runShell(const std::string& command) {
    FILE* pipe = popen(("(" + command + ") 2>&1").c_str(), "r");
    if (!pipe) return {-1, "popen failed: " + command};
    std::string output;
    char buffer[4096];
    while (size_t n = fread(buffer, 1, sizeof(buffer), pipe)) output.append(buffer, n);
    const int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), output};
}

// `bvhlab ARGS 2>&1`: its exit code and everything it printed.
inline Result run(const std::string& args) { return runShell(test::bvhlabProgram() + " " + args); }

}  // namespace bvhlab::test
