// Scratch folders for tests: one per name and test process under the system's temp directory
// (e.g. /tmp/bvhlab_test_batch_12345), so that two test runs on one machine (a CI clone next
// to a working tree) never write into each other's files. Removed when the process exits.
#pragma once

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace bvhlab::test {

inline std::filesystem::path scratchDir(const std::string& name) {
    struct Owned {
        std::vector<std::filesystem::path> dirs;
        ~Owned() {
            std::error_code ignored;
            for (const auto& d : dirs) std::filesystem::remove_all(d, ignored);
        }
    };
    static Owned owned;
    const auto dir = std::filesystem::temp_directory_path() / fmt::format("bvhlab_test_{}_{}", name, getpid());
    if (std::find(owned.dirs.begin(), owned.dirs.end(), dir) == owned.dirs.end()) owned.dirs.push_back(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace bvhlab::test
