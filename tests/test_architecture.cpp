// The include arrows of docs/architecture.md ("Layers"): every #include "..." in framework/,
// accel/ and apps/ points to a folder its own folder may use. A header can be included from
// anywhere the build lets it, so this test is what keeps the layers layered.
#include "tests/support/test_paths.h"

#include <gtest/gtest.h>

#include <algorithm>
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
    {"framework/api/bvhlab", {}},
    {"framework/core", {}},
    {"framework/config", {"framework/core"}},
    {"framework/scene", {"framework/core"}},
    {"framework/scene/readers", {"framework/core", "framework/scene"}},
    {"framework/render", {"framework/core", "framework/config", "framework/scene"}},
    {"framework/io", {"framework/core", "framework/config", "framework/scene", "framework/render"}},
    {"framework/report", {"framework/core", "framework/config", "framework/scene", "framework/render"}},
    {"accel/naive", {"framework/core"}},
    {"accel/embree", {"framework/core", "framework/config"}},
    {"accel/grid", {}},    // a plugin: <bvhlab/...> only
    {"accel/kdtree", {}},  // a plugin: <bvhlab/...> only
    {"accel/octree", {}},  // a plugin: <bvhlab/...> only
    {"accel/bvh/simd", {"framework/core"}},
    {"accel/bvh/layout", {"framework/core", "accel/bvh/simd"}},
    // Builders and traversal may use framework/config: their env keys sit beside the Config fields they fill.
    {"accel/bvh/builders", {"framework/core", "framework/config", "accel/bvh/simd", "accel/bvh/layout"}},
    {"accel/bvh/traverse", {"framework/core", "framework/config", "accel/bvh/simd", "accel/bvh/layout"}},
    {"accel/bvh",
     {"framework/core", "framework/config", "accel/bvh/simd", "accel/bvh/layout", "accel/bvh/builders",
      "accel/bvh/traverse"}},
    {"accel/plugins", {"framework/core", "framework/config", "accel/bvh/builders"}},
    {"accel/twolevel", {"framework/core", "accel/bvh/simd", "accel/bvh/layout", "accel/bvh/builders"}},
    {"accel",
     {"framework/core", "framework/config", "accel/naive", "accel/embree", "accel/bvh", "accel/plugins",
      "accel/twolevel"}},
    // Verification reaches the structures it compares with through the registry alone.
    {"accel/verify", {"framework/core", "framework/config", "framework/scene", "framework/render", "accel"}},
};

// apps/ sees all of framework/ and, of accel/, the registry, the plugin loader and the
// verification library: a structure is reached by its name and the Accelerator interface, a
// plugin file opened by the loader and what it adds registered by name, and `bvhlab check` and
// `bvhlab stress` are commands over accel/verify.
bool appMayInclude(const std::string& path) {
    return path.starts_with("framework/") || path.starts_with("apps/") || path.starts_with("accel/verify/") ||
           path == "accel/registry.h" || path == "accel/plugins/plugin_loader.h";
}

// The front ends that share the runtime and the folders of apps/ each may include besides its
// own: the runtime none (it serves the command line, not the other way round), the Python
// module only the runtime. The command line's folders may include any of apps/.
const std::map<std::string, std::vector<std::string>> kAppMayInclude = {
    {"apps/runtime", {}},
    {"apps/python", {"apps/runtime"}},
};

// The targets of a file's #include "..." (quoted) or #include <...> lines.
std::vector<std::string> includes(const fs::path& file, bool quoted) {
    static const std::regex quotedInclude(R"(^\s*#\s*include\s*"([^"]+)\")");
    static const std::regex angledInclude(R"(^\s*#\s*include\s*<([^>]+)>)");
    const std::regex& include = quoted ? quotedInclude : angledInclude;
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
            for (const std::string& target : includes(file, true)) {
                ++checked;
                const std::string targetFolder = fs::path(target).parent_path().generic_string();
                if (folder.starts_with("apps")) {
                    EXPECT_TRUE(appMayInclude(target)) << name << " includes " << target;
                    const auto front = kAppMayInclude.find(folder);
                    if (front != kAppMayInclude.end() && target.starts_with("apps/")) {
                        const auto& allowed = front->second;
                        EXPECT_TRUE(targetFolder == folder ||
                                    std::find(allowed.begin(), allowed.end(), targetFolder) != allowed.end())
                            << name << " includes " << target << ", which " << folder << " may not use";
                    }
                    continue;
                }
                const auto allowed = kMayInclude.find(folder);
                ASSERT_NE(allowed, kMayInclude.end()) << folder << " has no entry in the layer table";
                const bool ok = targetFolder == folder || std::find(allowed->second.begin(), allowed->second.end(),
                                                                    targetFolder) != allowed->second.end();
                EXPECT_TRUE(ok) << name << " includes " << target << ", which " << folder << " may not use";
            }
        }
    }
    EXPECT_GT(checked, 100u);
}

// CLI11 is the command line's: the runtime and the Python module compile without it, so neither
// includes it, nor a header of the command line that would bring it.
TEST(Architecture, TheRuntimeAndThePythonModuleDoNotIncludeCli11) {
    const fs::path source = bvhlab::test::sourceTree();
    size_t files = 0;
    for (const char* folder : {"apps/runtime", "apps/python"})
        for (const fs::path& file : sourcesUnder(source / folder)) {
            ++files;
            for (const std::string& target : includes(file, false))
                EXPECT_FALSE(target.starts_with("CLI/"))
                    << fs::relative(file, source).string() << " includes <" << target << ">";
        }
    EXPECT_GT(files, 20u);
}

// The tests of framework/ and accel/ stand below the program as their sources do: they reach
// the keys, the reference structures and the checks through accel/verify, never through apps/.
TEST(Architecture, TestsOfFrameworkAndAccelIncludeNoAppHeader) {
    const fs::path source = bvhlab::test::sourceTree();
    size_t checked = 0;
    for (const char* top : {"tests/framework", "tests/accel"})
        for (const fs::path& file : sourcesUnder(source / top)) {
            ++checked;
            for (const std::string& target : includes(file, true))
                EXPECT_FALSE(target.starts_with("apps/"))
                    << fs::relative(file, source).generic_string() << " includes " << target;
        }
    EXPECT_GT(checked, 30u);
}

TEST(Architecture, FrameworkHasNoSourceAtItsTop) {
    for (const auto& entry : fs::directory_iterator(fs::path(bvhlab::test::sourceTree()) / "framework")) {
        const auto ext = entry.path().extension();
        EXPECT_FALSE(ext == ".h" || ext == ".cpp") << entry.path() << " belongs in one of framework's layers";
    }
}

// The plugin API is one folder of headers that a plugin compiles against alone: they include one
// another as <bvhlab/NAME.h>, GLM and the standard library, never bvhlab's internal headers. The
// plugins of bvhlab's own tree and of its tests include nothing else of bvhlab's.
TEST(Architecture, ThePluginApiAndThePluginsIncludeOnlyThePluginApi) {
    const fs::path source = bvhlab::test::sourceTree();
    const fs::path api = source / "framework/api/bvhlab";
    auto checkAngled = [&](const fs::path& file) {
        for (const std::string& target : includes(file, false)) {
            const bool bvhlab = target.starts_with("bvhlab/") && fs::exists(api / target.substr(7));
            const bool glm = target.starts_with("glm/");
            const bool standard = target.find('/') == std::string::npos && target.find('.') == std::string::npos;
            EXPECT_TRUE(bvhlab || glm || standard)
                << fs::relative(file, source).string() << " includes <" << target << ">";
        }
    };
    size_t headers = 0;
    for (const auto& entry : fs::directory_iterator(api)) {
        EXPECT_EQ(entry.path().extension(), ".h") << entry.path() << ": the folder holds the API's headers only";
        EXPECT_TRUE(includes(entry.path(), true).empty()) << entry.path() << " includes a header by a quoted path";
        checkAngled(entry.path());
        ++headers;
    }
    EXPECT_GT(headers, 10u);
    for (const fs::path& folder :
         {source / "accel/grid", source / "accel/kdtree", source / "accel/octree", source / "tests/plugins"})
        for (const fs::path& file : sourcesUnder(folder)) {
            checkAngled(file);
            if (folder.filename() == "plugins") {
                EXPECT_TRUE(includes(file, true).empty()) << file;
            }
        }
}
