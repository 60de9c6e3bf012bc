// The two builds of the scan plugin (tests/plugins/scan.cpp), for the tests of a plugin rebuilt in place.
#pragma once

#include "tests/support/test_paths.h"

#include <filesystem>
#include <string>

namespace bvhlab::test {

// Copies build `variant` (1 or 2) of the scan plugin to DIR/plugins/scan.so, replacing the other.
inline std::filesystem::path installScan(const std::filesystem::path& dir, int variant) {
    std::filesystem::create_directories(dir / "plugins");
    std::filesystem::copy_file(testPlugins() + "/scan-" + std::to_string(variant) + "/scan.so",
                               dir / "plugins" / "scan.so", std::filesystem::copy_options::overwrite_existing);
    return dir / "plugins" / "scan.so";
}

}  // namespace bvhlab::test
