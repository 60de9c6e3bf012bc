// The include arrows of docs/architecture.md ("Layers"): every #include "..." in framework/,
// accel/ and apps/ points to a folder its own folder may use. A header can be included from
// anywhere the build lets it, so this test is what keeps the layers layered.
#include "tests/support/test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// Each folder (a library) and the folders it may include from, besides its own.
const std::map<std::string, std::vector<std::string>> kMayInclude = {
    {"framework/core", {}},
    {"framework/config", {"framework/core"}},
    {"framework/scene", {"framework/core"}},
    {"framework/scene/readers", {"framework/core", "framework/scene"}},
    {"framework/render", {"framework/core", "framework/config", "framework/scene"}},
    {"framework/io", {"framework/core", "framework/config", "framework/scene", "framework/render"}},
    {"framework/report", {"framework/core", "framework/config", "framework/scene", "framework/render"}},
    {"framework/robustness", {"framework/core", "framework/config", "framework/scene", "framework/render"}},
    {"framework/plugin", {"framework/core", "framework/config"}},
    {"accel/naive", {"framework/core"}},
    {"accel/embree", {"framework/core", "framework/config"}},
    {"accel/grid", {"framework/core", "framework/config", "framework/plugin"}},
    {"accel/bvh/simd", {"framework/core"}},
    {"accel/bvh/layout", {"framework/core", "accel/bvh/simd"}},
    {"accel/bvh/builders", {"framework/core", "accel/bvh/simd", "accel/bvh/layout"}},
    {"accel/bvh/traverse", {"framework/core", "accel/bvh/simd", "accel/bvh/layout"}},
    {"accel/bvh",
     {"framework/core", "framework/config", "framework/plugin", "accel/bvh/simd", "accel/bvh/layout",
      "accel/bvh/builders", "accel/bvh/traverse"}},
    {"accel", {"framework/core", "framework/config", "framework/plugin", "accel/naive", "accel/embree", "accel/bvh"}},
};

// apps/ sees all of framework/ and, of accel/, only the registry: a structure is reached by
// its name and the Accelerator interface.
bool appMayInclude(const std::string& path) {
    return path.starts_with("framework/") || path.starts_with("apps/") || path == "accel/registry.h";
}

std::vector<std::string> quotedIncludes(const fs::path& file) {
    static const std::regex include(R"(^\s*#\s*include\s*"([^"]+)\")");
    std::ifstream in(file);
    std::vector<std::string> out;
    std::smatch m;
    for (std::string line; std::getline(in, line);)
        if (std::regex_search(line, m, include)) out.push_back(m[1]);
    return out;
}

std::vector<fs::path> sourcesUnder(const fs::path& root) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        const auto ext = entry.path().extension();
        if (entry.is_regular_file() && (ext == ".h" || ext == ".cpp")) files.push_back(entry.path());
    }
    return files;
}

}  // namespace

TEST(Architecture, IncludesFollowTheLayers) {
    const fs::path source = bvhlab::test::sourceTree();
    size_t checked = 0;
    for (const char* top : {"framework", "accel", "apps"}) {
        for (const fs::path& file : sourcesUnder(source / top)) {
            const std::string folder = fs::relative(file.parent_path(), source).generic_string();
            const std::string name = fs::relative(file, source).generic_string();
            for (const std::string& target : quotedIncludes(file)) {
                ++checked;
                const std::string targetFolder = fs::path(target).parent_path().generic_string();
                if (folder.starts_with("apps")) {
                    EXPECT_TRUE(appMayInclude(target)) << name << " includes " << target;
                    continue;
                }
                const auto allowed = kMayInclude.find(folder);
                ASSERT_NE(allowed, kMayInclude.end()) << folder << " has no entry in the layer table";
                const bool ok = targetFolder == folder ||
                                std::find(allowed->second.begin(), allowed->second.end(), targetFolder) !=
                                    allowed->second.end();
                EXPECT_TRUE(ok) << name << " includes " << target << ", which " << folder << " may not use";
            }
        }
    }
    EXPECT_GT(checked, 100u);
}

TEST(Architecture, FrameworkHasNoSourceAtItsTop) {
    for (const auto& entry : fs::directory_iterator(fs::path(bvhlab::test::sourceTree()) / "framework")) {
        const auto ext = entry.path().extension();
        EXPECT_FALSE(ext == ".h" || ext == ".cpp") << entry.path() << " belongs in one of framework's layers";
    }
}
