// Every command that builds a structure takes a plugin's structure the same ways: found by name
// in the plugin folders, its keys as -D, in an env file and as NAME:Key=value. bvhlab's own grid
// (build/plugins/grid.so, a plugin like any other) stands for one. And what a user sees when a
// plugin is missing or a file found by name adds something else.
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <vector>

namespace bvhlab::test {
namespace {

namespace fs = std::filesystem;

// A folder with a small mesh, an SPD scene, Havran's tables in small and an env file that sets
// the grid's density; commands run in it with the scene cache in it too.
struct Workspace {
    fs::path dir = scratchDir("plugin_commands");
    Workspace() {
        std::ofstream(dir / "mesh.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\nv 0 0 1\n"
                                           "f 1 2 3\nf 2 4 3\nf 1 5 2\nf 3 4 5\n";
        std::ofstream(dir / "balls.nff") << "v\nfrom 0 -6 3\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 8 8\n"
                                            "l 4 -3 6\nf 1 0.75 0.33 0.8 0 100000 0 1\n"
                                            "p 3\n4 4 -0.5\n-4 4 -0.5\n0 -4 -0.5\ns 0 0 0.5 1\n";
        std::ofstream(dir / "havran_stats_grids.txt")
            << "Invariants\n balls gears lattice mount\nPrimaryRay[-] 64 64 64 64\n";
        std::ofstream(dir / "havran_stats_octrees.txt") << "BALLS\n N_IT 19.0\n N_TS 11.0\n";
        std::ofstream(dir / "grid.env") << "Grid::density 2\n";
    }
    // `bvhlab ARGS` in the workspace.
    Result run(const std::string& args) const {
        return runShell(
            fmt::format("cd {} && XDG_CACHE_HOME={}/cache {} {}", dir.string(), dir.string(), bvhlabProgram(), args));
    }
};

const char* kSmall = " -DCamera::width=16 -DCamera::height=12";

// The value a run's JSON (its "env" object, wherever it is) gives a key.
std::string envValue(const fs::path& file, const std::string& key) {
    std::ifstream in(file);
    const nlohmann::json j = nlohmann::json::parse(in);
    const nlohmann::json* found = nullptr;
    auto search = [&](auto&& self, const nlohmann::json& node) -> void {
        if (found || !node.is_structured()) return;
        if (node.is_object() && node.contains("env") && node["env"].contains(key)) found = &node["env"][key];
        for (const auto& child : node) self(self, child);
    };
    search(search, j);
    return found ? (*found)["value"].get<std::string>() : "(absent)";
}

TEST(PluginCommands, EveryCommandTakesAPluginFoundByNameWithItsKeys) {
    const Workspace w;
    Result r = w.run(fmt::format("render -DASDS::type=grid -DGrid::density=3{} --out render", kSmall));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(envValue(w.dir / "render.json", "Grid::density"), "3");
    r = w.run(fmt::format("render --env grid.env -DASDS::type=grid{} --out render_env", kSmall));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(envValue(w.dir / "render_env.json", "Grid::density"), "2");

    r = w.run("rays --scene mesh.obj --kind primary --out rays.bin");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // The key by -D, in an env file and as NAME:Key=value, the plugin found by name each time.
    for (const std::string& command : std::vector<std::string>{
             "raycast --scene mesh.obj --rays rays.bin --out hits.bin -DASDS::type=grid -DGrid::density=3",
             fmt::format("batch --scenes mesh.obj --accel grid --env grid.env{} --out batch_env", kSmall),
             "bench --scenes mesh.obj --accel grid -DGrid::density=3 --builds 1 --passes 1 --out bench.json",
             "stress --accel grid -DGrid::density=3 --parts watertight --rays 16 --out stress.json",
             "tradeoff --builders --accel grid:Grid::density=3 -DGrid::objects=2 --scenes mesh.obj --quick --out "
             "tradeoff",
             "check --accel grid:Grid::density=3 --checks batch", "check --accel grid -DGrid::density=3 --checks batch",
             "spd balls.nff --accel grid -DGrid::density=3 -DSpd::reference=. --out spd --quiet"}) {
        r = w.run(command);
        EXPECT_EQ(r.exitCode, 0) << command << "\n" << r.output;
    }
    r = w.run(fmt::format(
        "batch --scenes mesh.obj --accel grid:Grid::density=3,sahbvh8 -DGrid::objects=2{} --out batch", kSmall));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("grid:Grid::density=3"), std::string::npos) << r.output;
    // A label in a file name has no ':' or '=' (labelAsFileName).
    EXPECT_TRUE(fs::exists(w.dir / "batch" / "jobs" / "mesh__grid_Grid__density-3.json"));
    EXPECT_TRUE(fs::exists(w.dir / "tradeoff" / "mesh" / "grid_Grid__density-3.json"));

    const fs::path python = fs::path(bvhlabProgram()).parent_path() / "python";
    if (!fs::exists(python)) return;  // a build without the module (the sanitizer's)
    r =
        runShell(fmt::format("cd {} && PYTHONPATH={} /usr/bin/python3 -c \"import bvhlab; "
                             "accel = bvhlab.build(bvhlab.load_scene('mesh.obj'), 'grid', env={{'Grid::density': 3}}); "
                             "print(accel.stats['name'] if 'name' in accel.stats else 'built')\"",
                             w.dir.string(), python.string()));
    EXPECT_EQ(r.exitCode, 0) << r.output;
}

TEST(PluginCommands, AKeyOfAPluginThatIsNotLoadedSaysSo) {
    const Workspace w;
    for (const std::string& args :
         {std::string("render -DKdMed::maxLeaf=4"), std::string("bench --accel sahbvh8 -DKdMed::maxLeaf=4")}) {
        const Result r = w.run(args + " --out x");
        EXPECT_EQ(r.exitCode, 1) << r.output;
        EXPECT_NE(r.output.find("-DKdMed::maxLeaf: unknown key 'KdMed::maxLeaf': no section KdMed:: in bvhlab or a "
                                "loaded plugin. If it is a plugin's key, load the plugin"),
                  std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find("plugins"), std::string::npos) << r.output;  // the folders searched
    }
    std::ofstream(w.dir / "kdmed.env") << "KdMed::maxLeaf 4\n";
    const Result r = w.run("keys --env kdmed.env");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("kdmed.env:1: unknown key 'KdMed::maxLeaf'"), std::string::npos) << r.output;
}

TEST(PluginCommands, AFileFoundByNameThatAddsAnotherNameSaysWhatItAdds) {
    const Workspace w;
    const fs::path folder = w.dir / "my_plugins";
    fs::create_directories(folder);
    fs::copy_file(fs::path(bvhlabProgram()).parent_path() / "plugins" / "grid.so", folder / "bsptree.so",
                  fs::copy_options::overwrite_existing);
    const Result r = runShell(fmt::format("BVHLAB_PLUGIN_PATH={} {} render -DASDS::type=bsptree --out {}",
                                          folder.string(), bvhlabProgram(), (w.dir / "x").string()));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(
        r.output.find(fmt::format("unknown accelerator 'bsptree': the plugin {} was loaded for it, but it adds grid, "
                                  "not 'bsptree'",
                                  (folder / "bsptree.so").string())),
        std::string::npos)
        << r.output;
}

TEST(PluginCommands, NoGlobalEnvKeepsTheDefaultStructureAndEmptyLinesEraseNothing) {
    Result r = run("keys --no-global-env");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("ASDS::type sahbvh8  # default"), std::string::npos) << r.output;
    const std::string global = sourceTree() + "/env/global.env", sibenik = sourceTree() + "/env/scenes/sibenik.env";
    r = run(fmt::format("keys --no-global-env --env {} --env {}", sibenik, global));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("Scene::file sibenik.obj  # " + sibenik), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("Camera::from -17 -9 0  # " + sibenik), std::string::npos) << r.output;
}

TEST(PluginCommands, TheProgramBuildsBvhlabsOwnPlugins) {
    // README command 1 builds the target bvhlab only: the plugins bvhlab ships must come with it.
    const fs::path build = fs::path(bvhlabProgram()).parent_path();
    if (!fs::exists(build / "build.ninja")) GTEST_SKIP() << "not a Ninja build: " << build;
    const Result r = runShell(fmt::format("ninja -C {} -t query bvhlab", build.string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("grid"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace bvhlab::test
