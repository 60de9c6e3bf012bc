// docs/env-keys.md lists exactly the registered keys and accelerators (regenerate it with
// `bvhlab keys > docs/env-keys.md`), env/global.env uses only known keys, every path of the
// repository that a doc names exists, and docs/plugins.md describes the whole plugin API.
#include "accel/registry.h"
#include "apps/runtime/program_keys.h"
#include "tests/support/cli_run.h"
#include "tests/support/test_paths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

using namespace bvhlab;

// As the program prints it: its own keys and those of the plugins it ships (build/plugins), no
// user's (BVHLAB_PLUGIN_PATH unset), warnings aside.
TEST(Docs, EnvKeyListMatchesRegistry) {
    std::ifstream in(test::sourceTree() + "/docs/env-keys.md");
    ASSERT_TRUE(in) << "docs/env-keys.md is missing";
    std::stringstream text;
    text << in.rdbuf();
    const test::Result keys =
        test::runShell("env -u BVHLAB_PLUGIN_PATH " + test::bvhlabProgram() + " keys 2>/dev/null");
    ASSERT_EQ(keys.exitCode, 0) << keys.output;
    EXPECT_EQ(text.str(), keys.output) << "run: build/bvhlab keys > docs/env-keys.md";
    EXPECT_NE(keys.output.find("| `grid` |"), std::string::npos);  // the shipped plugins are listed
}

TEST(Docs, GlobalEnvLoads) {
    Env env(programKeys());
    EXPECT_NO_THROW(env.loadFile(test::sourceTree() + "/env/global.env"));
}

// Each key's declared default is a value it accepts (a default out of its own range would be
// used silently, since defaults are not parsed from a file).
TEST(Docs, EveryDeclaredDefaultIsValid) {
    for (const auto& [name, key] : programKeys().keys()) {
        Env env(programKeys());
        EXPECT_NO_THROW(env.set(name, key.defaultValue, "default")) << name << " = '" << key.defaultValue << "'";
    }
}

// Every path of the repository that the docs, the README and the CMake files name exists
// (`framework/scene/scene_cache.{h,cpp}` is two paths; a comma-separated list is several).
// Paths a user is told to create are listed here as examples.
TEST(Docs, EveryRepositoryPathTheyNameExists) {
    namespace fs = std::filesystem;
    const fs::path root(test::sourceTree());
    const std::set<std::string> examples = {"accel/bih"};
    std::vector<fs::path> files = {root / "README.md", root / "CMakeLists.txt"};
    for (const char* folder : {"docs", "framework", "accel", "apps", "tests"})
        for (const auto& entry : fs::recursive_directory_iterator(root / folder))
            if (entry.path().extension() == ".md" || entry.path().filename() == "CMakeLists.txt")
                files.push_back(entry.path());
    const std::regex pathPattern(R"((^|[^\w./-])((framework|accel|apps|tests|env|docs)/[\w./{},*-]*[\w}*]))");
    // A path, or with a '*' (wide_bvh.*) some file that starts as it does.
    const auto exists = [&](const std::string& path) {
        const size_t star = path.find('*');
        if (star == std::string::npos) return fs::exists(root / path);
        const fs::path prefix = root / path.substr(0, star);
        if (!fs::is_directory(prefix.parent_path())) return false;
        for (const auto& entry : fs::directory_iterator(prefix.parent_path()))
            if (entry.path().string().starts_with(prefix.string())) return true;
        return false;
    };
    for (const fs::path& file : files) {
        std::ifstream in(file);
        size_t lineNumber = 0;
        for (std::string line; std::getline(in, line);) {
            ++lineNumber;
            for (std::sregex_iterator m(line.begin(), line.end(), pathPattern), end; m != end; ++m) {
                std::string text = (*m)[2];
                std::vector<std::string> paths;
                if (const size_t open = text.find('{'), close = text.find('}');
                    open != std::string::npos && close != std::string::npos && open < close) {
                    std::stringstream alternatives(text.substr(open + 1, close - open - 1));
                    for (std::string a; std::getline(alternatives, a, ',');)
                        paths.push_back(text.substr(0, open) + a + text.substr(close + 1));
                } else {
                    std::stringstream list(text);
                    for (std::string p; std::getline(list, p, ',');) paths.push_back(p);
                }
                for (const std::string& path : paths)
                    EXPECT_TRUE(examples.count(path) || exists(path))
                        << fs::relative(file, root).string() << ":" << lineNumber << " names " << path;
            }
        }
    }
}

// docs/adding-an-accelerator.md tells a new structure how to test every primitive kind and
// names every file of bvhlab's own that it touches.
TEST(Docs, AddingAnAcceleratorCoversEveryPrimitiveKindAndFile) {
    std::ifstream in(test::sourceTree() + "/docs/adding-an-accelerator.md");
    std::stringstream text;
    text << in.rdbuf();
    for (const char* needed : {"intersectTriangle", "intersectQuadric", "validQuadrics", "sphereBase", "coneBase",
                               "countQuadricTest", "accel/CMakeLists.txt", "accel/registry.cpp",
                               "tests/test_architecture.cpp", "docs/env-keys.md", "leafBound", "depthBound"})
        EXPECT_NE(text.str().find(needed), std::string::npos) << needed;
}

// docs/plugins.md's reference describes the plugin API: every type and virtual function of the
// headers of framework/api/bvhlab/, and the cost constants a builder is given.
TEST(Docs, ThePluginReferenceDescribesEveryTypeOfThePluginApi) {
    namespace fs = std::filesystem;
    const fs::path root(test::sourceTree());
    std::set<std::string> names = {"cTraversal", "cIntersect", "BVH::cTraversal", "BVH::cIntersect"};
    const std::regex declaration(
        R"(^(?:struct|class|enum class) (?:alignas\(\d+\) )?(\w+)[^;]*$|virtual [^(]*\b(\w+)\()");
    size_t headers = 0;
    for (const auto& header : fs::directory_iterator(root / "framework/api/bvhlab")) {
        ++headers;
        std::ifstream in(header.path());
        for (std::string line; std::getline(in, line);) {
            std::smatch m;
            if (std::regex_search(line, m, declaration)) names.insert(m[m[1].matched ? 1 : 2].str());
        }
    }
    EXPECT_GT(headers, 10u);
    names.erase("AnyField");  // how abi.h counts a struct's fields, nothing a plugin uses
    std::ifstream in(root / "docs/plugins.md");
    std::stringstream text;
    text << in.rdbuf();
    const size_t reference = text.str().find("\n## Reference\n");
    ASSERT_NE(reference, std::string::npos);
    const std::string referenceText = text.str().substr(reference);
    for (const std::string& name : names)
        EXPECT_TRUE(std::regex_search(referenceText, std::regex("\\b" + name + "\\b"))) << name;
}

// The study of docs/results/ that reproduces the report's Table 1 (its title names it) has the
// default structure beside the report's two, and says what it was run at.
TEST(Docs, ResultsHaveTheDefaultStructureAndTheirCommit) {
    namespace fs = std::filesystem;
    std::string table1;
    for (const auto& entry : fs::directory_iterator(fs::path(test::sourceTree()) / "docs/results")) {
        std::ifstream in(entry.path());
        std::string title;
        std::getline(in, title);
        if (title.find("Table 1") == std::string::npos) continue;
        std::stringstream text;
        text << title << '\n' << in.rdbuf();
        table1 = text.str();
    }
    ASSERT_FALSE(table1.empty()) << "no study under docs/results/ is titled with the report's Table 1";
    Env globalEnv(programKeys());
    globalEnv.loadFile(test::sourceTree() + "/env/global.env");
    const std::string defaultStructure = globalEnv.get(keys::ASDS::type);
    for (const std::string& accel :
         {defaultStructure, std::string("sahbvh"), std::string("tdbvh"), std::string("embree")})
        EXPECT_NE(table1.find("| conference | " + accel + " |"), std::string::npos) << accel;
    EXPECT_TRUE(std::regex_search(table1, std::regex("at commit [0-9a-f]{7}")));
}
