// What every subcommand does alike, from the traps a new user met in a first hour (issue 9):
// --version, --env and -D everywhere, env layering on env/global.env, a scene named by its file
// or its env file seen from its own camera, the run recorded in the JSON, --threads and --scenes
// with one meaning, output paths checked alike, a too-large image refused up front, progress
// lines and --quiet (the progress line itself: test_progress.cpp).
#include "apps/runtime/program_keys.h"
#include "framework/io/ray_file.h"
#include "framework/scene/scene_cache.h"
#include "tests/support/cli_run.h"
#include "tests/support/json_file.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <regex>

using namespace bvhlab;

namespace {

using test::readJson;

using test::Result;
using test::run;
namespace fs = std::filesystem;

fs::path tempDir() { return test::scratchDir("cli_conventions"); }

// Scene::dir's default: the scenes beside the repository.
fs::path scenesDir() { return fs::path(test::sourceTree()) / ".." / "shared" / "scenes"; }

// A unit quad in z = 0, in a scene file no env file names.
fs::path quadScene() {
    const fs::path file = tempDir() / "quad.obj";
    std::ofstream(file) << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
    return file;
}

const std::string kTiny = " -DCamera::width=16 -DCamera::height=12 ";

}  // namespace

TEST(CliConventions, VersionPrintsVersionAndCommit) {
    const Result r = run("--version");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex(R"(^bvhlab \d+\.\d+ \(commit \S+\))"))) << r.output;
}

TEST(CliConventions, KeysResolvesEnvFilesAndOverrides) {
    const fs::path env = tempDir() / "bins.env";
    std::ofstream(env) << "BVH::bins 32\n";
    const Result r = run("keys --env " + env.string() + " -DBVH::leafCap=2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("BVH::bins 32  # " + env.string() + ":1"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("BVH::leafCap 2  # -DBVH::leafCap"), std::string::npos) << r.output;
    // Without them, the Markdown reference as before.
    EXPECT_NE(run("keys").output.find("| `BVH::bins` |"), std::string::npos);
}

// `keys` shows the value that runs beside the default: env/global.env's in the reference, every
// layer's (with where it comes from) when resolving; a file named twice is read once.
TEST(CliConventions, KeysShowTheValueThatRunsBesideTheDefault) {
    const std::string reference = run("keys").output;
    const size_t row = reference.find("| `Output::heatmap` |");
    ASSERT_NE(row, std::string::npos) << reference;
    const std::string heatmap = reference.substr(row, reference.find('\n', row) - row);
    EXPECT_NE(heatmap.find("| `false` | `true` |"), std::string::npos) << heatmap;  // default, then global.env's

    const std::string global = test::sourceTree() + "/env/global.env";
    const Result r = run("keys --env env/global.env -DBVH::bins=8");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("# env files: " + global + "\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("Output::heatmap true  # " + global + ":"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(default: false)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("BVH::bins 8  # -DBVH::bins (default: 16)"), std::string::npos) << r.output;
}

// The two slips of the Key=value forms get the right form named: `Key=value` in an env file,
// `-DKey value` on the command line.
TEST(CliConventions, KeyValueSlipsGetTheRightForm) {
    const fs::path env = tempDir() / "equals.env";
    std::ofstream(env) << "# a comment\nASDS::type=sahbvh\n";
    Result r = run("keys --env " + env.string());
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find(env.string() + ":2: 'ASDS::type=sahbvh': env lines are 'Section::key value', with a "
                                           "space; write 'ASDS::type sahbvh'"),
              std::string::npos)
        << r.output;
    r = run("render -DASDS::type grid --out " + (tempDir() / "slip").string());
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("-DASDS::type grid: -D takes Section::key=value as one word; write -DASDS::type=grid"),
              std::string::npos)
        << r.output;
}

// Every subcommand that takes --accel checks its names and their :Key=value overrides before any
// work (no scene is loaded), and the error names what the user typed, not a -D they never wrote.
TEST(CliConventions, AccelListsAreCheckedFirstAndNamedAsTyped) {
    const fs::path nff = tempDir() / "one.nff";
    std::ofstream(nff) << "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 30\nhither 1\nresolution 4 4\n"
                          "l 0 0 5\nf 1 1 1 1 0 0 0 1\np 3\n-1 -1 0\n1 -1 0\n0 1 0\n";
    const std::string out = (tempDir() / "accel_check").string();
    for (const std::string& command :
         {"bench --out " + out + ".json", "stress --out " + out + ".json", "spd " + nff.string() + " --out " + out,
          "tradeoff --out " + out, "tradeoff --builders --out " + out}) {
        SCOPED_TRACE(command);
        Result r = run(command + " --accel sahbvh,bsptree");
        EXPECT_EQ(r.exitCode, 1) << r.output;
        EXPECT_NE(r.output.find("--accel bsptree: unknown accelerator 'bsptree': none of bvhlab's"), std::string::npos)
            << r.output;
        EXPECT_EQ(r.output.find("triangles ("), std::string::npos) << "a scene was loaded first:\n" << r.output;
        r = run(command + " --accel sahbvh:BVH::binz=8");
        EXPECT_EQ(r.exitCode, 1) << r.output;
        EXPECT_NE(r.output.find("--accel sahbvh:BVH::binz=8: unknown key 'BVH::binz'"), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("-DBVH::binz"), std::string::npos) << r.output;
    }
}

// A float range is printed as declared, not as its double widening (0.0010000000474974513).
TEST(CliConventions, FloatRangesArePrintedAsDeclared) {
    constexpr FloatKey key{"Test::epsilon", "0.01", 0.001f, 1000.0f, "a float key declared with float bounds"};
    EXPECT_EQ(envKeyType(key.declaration()), "float 0.001..1000");
}

// --env layers on env/global.env; --no-global-env starts from the keys' defaults.
TEST(CliConventions, EnvFilesLayerOnGlobalEnv) {
    const fs::path env = tempDir() / "small.env";
    std::ofstream(env) << "Camera::width 16\nCamera::height 12\n";
    const fs::path out = tempDir() / "layered";
    Result r = run("render --env " + env.string() + " --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json j = readJson(out.string() + ".json");
    EXPECT_EQ(j["env"]["SetRayTracing::depthLimit"]["value"], "3");
    EXPECT_NE(j["env"]["SetRayTracing::depthLimit"]["from"].get<std::string>().find("global.env"), std::string::npos);
    EXPECT_EQ(j["env"]["Camera::width"]["value"], "16");
    ASSERT_EQ(j["env_files"].size(), 2u);
    EXPECT_NE(j["env_files"][0].get<std::string>().find("global.env"), std::string::npos);

    r = run("render --no-global-env --env " + env.string() + " --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    j = readJson(out.string() + ".json");
    EXPECT_EQ(j["env"]["SetRayTracing::depthLimit"]["from"], "default");
    EXPECT_EQ(j["env_files"].size(), 1u);
}

TEST(CliConventions, RenderRecordsTheSceneReadTheCommandAndTheTime) {
    const fs::path scene = quadScene(), out = tempDir() / "record";
    const Result r = run("render --scene " + scene.string() + kTiny + "--out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json j = readJson(out.string() + ".json");
    EXPECT_EQ(j["scene_file"]["file"], fs::absolute(scene).lexically_normal().string());
    const SceneCacheKey key = sceneCacheKey(scene);
    EXPECT_EQ(j["scene_file"]["size"], key.size);
    EXPECT_EQ(j["scene_file"]["crc32"], fmt::format("{:08x}", key.crc32));
    EXPECT_EQ(j["env"]["Scene::file"]["value"], fs::absolute(scene).lexically_normal().string());
    EXPECT_EQ(j["env"]["Scene::file"]["from"], "--scene");
    const std::string command = j["run"]["command_line"];
    EXPECT_NE(command.find("render --scene " + scene.string()), std::string::npos) << command;
    EXPECT_TRUE(
        std::regex_match(j["run"]["started"].get<std::string>(), std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")))
        << j["run"]["started"];
}

// --scene-env gives a scene its camera; a scene name not found says which names there are.
TEST(CliConventions, SceneEnvGivesTheCamera) {
    const fs::path scene = quadScene(), sceneEnv = tempDir() / "quad_view.env", out = tempDir() / "view";
    std::ofstream(sceneEnv) << "Camera::from 0 0 7\nCamera::at 0 0 0\nCamera::up 0 1 0\n";
    Result r =
        run("render --scene " + scene.string() + " --scene-env " + sceneEnv.string() + kTiny + "--out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(readJson(out.string() + ".json")["env"]["Camera::from"]["value"], "0 0 7");

    r = run("render --scene no_such_scene --out " + out.string());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("no_such_scene: no such file here or in Scene::dir, and"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("Scene::dir is "), std::string::npos) << r.output;  // and how to set it
    EXPECT_NE(r.output.find("and no scene env file env/scenes/no_such_scene.env"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("munich"), std::string::npos) << r.output;  // the names there are
}

// --scene NAME.ext looks in Scene::dir, as -DScene::file=NAME.ext does.
TEST(CliConventions, SceneFileIsLookedForInSceneDir) {
    const fs::path dir = tempDir() / "scene_dir";
    fs::create_directories(dir);
    std::ofstream(dir / "quad_in_dir.obj") << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
    const fs::path out = tempDir() / "in_dir";
    const Result r =
        run("render --scene quad_in_dir.obj -DScene::dir=" + dir.string() + kTiny + "--out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("scene quad_in_dir: 2 triangles"), std::string::npos) << r.output;
}

// `--scene munich` and `--scene .../munich.ply` both take env/scenes/munich.env's view.
TEST(SharedScenesCli, SceneByNameOrFileTakesItsOwnView) {
    if (!fs::exists(scenesDir() / "munich.ply")) GTEST_SKIP() << "no munich.ply in " << scenesDir();
    for (const std::string& scene : {std::string("munich"), (scenesDir() / "munich.ply").string()}) {
        SCOPED_TRACE(scene);
        const fs::path out = tempDir() / "munich";
        const Result r = run("render --scene " + scene + kTiny + "-DSetRayTracing::depthLimit=1 --out " + out.string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        const nlohmann::json j = readJson(out.string() + ".json");
        EXPECT_EQ(j["env"]["Camera::from"]["value"], "480 -820 520");
        EXPECT_NE(j["env"]["Camera::from"]["from"].get<std::string>().find("munich.env"), std::string::npos);
        EXPECT_NE(j["scene_file"]["file"].get<std::string>().find("munich.ply"), std::string::npos);
    }
}

TEST(CliConventions, OutputPathsAreCheckedAlikeEverywhere) {
    Result r = run("render --out \"\"");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("--out: empty path"), std::string::npos) << r.output;
    r = run("render --out " + tempDir().string() + "/");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("names a folder"), std::string::npos) << r.output;

    // raycast creates the folder of its output, as render does.
    const fs::path rays = tempDir() / "one.rays", hits = tempDir() / "missing" / "dir" / "x.hits";
    writeRayFile(rays, {{Vec3(0.0f, 0.0f, 5.0f), Vec3(0.0f, 0.0f, -1.0f), 0.0f, kInfinity}});
    r = run("raycast --scene " + quadScene().string() + " --rays " + rays.string() + " --out " + hits.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(readHitFile(hits).size(), 1u);
}

// --threads N (0 = all) on every subcommand that traces. Each run below stops at a missing
// scene, after its options were accepted.
TEST(CliConventions, ThreadsMeansTheSameEverywhere) {
    const fs::path out = tempDir() / "threads";
    Result r = run("render --threads 1" + kTiny + "--out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(readJson(out.string() + ".json")["threads"], 1);
    EXPECT_EQ(readJson(out.string() + ".json")["env"]["SetRayTracing::threads"]["from"], "--threads");
    for (const std::string command : {"batch", "bench", "tradeoff", "raycast --rays x --out y", "render"}) {
        r = run(command + " --threads 0 --scenes missing.env --scene missing.obj");
        EXPECT_EQ(r.output.find("--threads"), std::string::npos) << command << ": " << r.output;
    }
}

// --scenes takes scene files as well as env and .list files: a bench over a bare OBJ.
TEST(CliConventions, ScenesTakeSceneFiles) {
    const fs::path out = tempDir() / "bench.json";
    const Result r = run("bench --scenes " + quadScene().string() + kTiny +
                         "--accel sahbvh --threads 1 --builds 1 --passes 1 --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json j = readJson(out);
    ASSERT_FALSE(j["rows"].empty());
    EXPECT_EQ(j["rows"][0]["scene"], "quad");
}

// A scene file takes the env file that names a file of its name, wherever it lives (a copy, an
// installed bvhlab's Scene::dir elsewhere), compressed or not: a10.obj is seen as a10.env says.
TEST(CliConventions, SceneFileFindsItsEnvByItsName) {
    for (const std::string name : {"a10.obj", "a10.obj.gz"}) {
        SCOPED_TRACE(name);
        const fs::path dir = tempDir() / ("copy_of_" + name);
        fs::create_directories(dir);
        // gzopen reads a file that is not gzip as it is: a plain OBJ under the .gz name will do.
        std::ofstream(dir / name) << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
        const fs::path out = dir / "render";
        const Result r = run("render --scene " + (dir / name).string() + kTiny + "--out " + out.string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        const std::string a10Env = (fs::path(test::sourceTree()) / "env" / "scenes" / "a10.env").string();
        EXPECT_NE(r.output.find("scene env: " + a10Env), std::string::npos) << r.output;
        const nlohmann::json j = readJson(out.string() + ".json");
        EXPECT_EQ(j["env"]["Camera::from"]["value"], "14 -13 8");
        EXPECT_EQ(j["env"]["Camera::from"]["from"], a10Env + ":3");
        EXPECT_TRUE(j["run"]["warnings"].empty()) << j["run"].dump();
    }
}

// A scene file no env file names is seen with the default camera and lights, and the run says so
// on stderr and in its JSON.
TEST(CliConventions, SceneFileWithoutSceneEnvIsSaid) {
    const fs::path scene = quadScene(), out = tempDir() / "no_scene_env";
    const Result r = run("render --scene " + scene.string() + kTiny + "--out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string said = scene.string() + ": no scene env file in ";
    EXPECT_NE(r.output.find("warning: " + said), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("a view framing the scene and one light above the camera"), std::string::npos) << r.output;
    const nlohmann::json warnings = readJson(out.string() + ".json")["run"]["warnings"];
    ASSERT_EQ(warnings.size(), 1u) << warnings.dump();
    EXPECT_EQ(warnings[0].get<std::string>().rfind(said, 0), 0u) << warnings.dump();
}

// --scenes takes a scene's name as --scene does (teapots for env/scenes/teapots.env), in every
// command; a scene file missing under Scene::dir names the key to set, in every command.
TEST(CliConventions, ScenesTakeNamesAndAMissingSceneNamesTheKey) {
    const std::string nowhere = (tempDir() / "nowhere").string();
    const std::string hint = "Scene::dir is " + nowhere +
                             " (from -DScene::dir; set it with -DScene::dir=... or a "
                             "line 'Scene::dir ...' in an env file)";
    const std::string teapotsEnv = (fs::path(test::sourceTree()) / "env" / "scenes" / "teapots.env").string();
    for (const std::string command : {"render --scene teapots", "bench --scenes teapots", "batch --scenes teapots",
                                      "tradeoff --quick --scenes teapots", "rays --scene teapots"}) {
        SCOPED_TRACE(command);
        const std::string out = (tempDir() / "teapots" / command.substr(0, command.find(' '))).string();
        const Result r = run(command + " -DScene::dir=" + nowhere + " --out " + out);
        EXPECT_EQ(r.exitCode, 1) << r.output;
        EXPECT_NE(r.output.find("scene file teapots.obj (Scene::file, from " + teapotsEnv + ":2): no such file " +
                                nowhere + "/teapots.obj; " + hint),
                  std::string::npos)
            << r.output;
    }
}

// Nothing traced is n/a, not zero: shadows off leaves the shadow row without figures.
TEST(CliConventions, NothingTracedIsNotApplicable) {
    const fs::path out = tempDir() / "noshadows";
    const Result r = run("render -DSetRayTracing::shadows=false" + kTiny + "--out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json j = readJson(out.string() + ".json");
    EXPECT_EQ(j["shadow"]["queries"], 0);
    EXPECT_TRUE(j["shadow"]["t_r_us"].is_null());
    EXPECT_TRUE(j["shadow"]["n_it"].is_null());
    EXPECT_FALSE(j["primary"]["t_r_us"].is_null());
    const std::string shadowLine = r.output.substr(r.output.find("  shadow rays"));
    EXPECT_NE(shadowLine.substr(0, shadowLine.find('\n')).find("n/a"), std::string::npos) << r.output;
}

// The statistics footer says "shadows off" only when they are.
TEST(CliConventions, TheFooterSaysWhyShadowRaysWereNotCast) {
    const fs::path out = tempDir() / "footer";
    Result r = run("render" + kTiny + "--out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("shadows off"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("shadow rays not cast: "), std::string::npos) << r.output;
    r = run("render -DSetRayTracing::shadows=false" + kTiny + "--out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("shadows off: no shadow rays cast ("), std::string::npos) << r.output;
}

#if !defined(__SANITIZE_ADDRESS__)  // ASan reserves more address space than any ulimit -v below
TEST(CliConventions, ImageTooLargeForMemoryIsRefusedUpFront) {
    const Result r =
        test::runShell("ulimit -v 3000000; " + test::bvhlabProgram() +
                       " render -DCamera::width=16384 -DCamera::height=16384 --out " + (tempDir() / "huge").string());
    const std::string& output = r.output;
    EXPECT_EQ(r.exitCode, 1) << output;
    EXPECT_NE(output.find("a 16384 x 16384 image needs about"), std::string::npos) << output;
    EXPECT_NE(output.find("ulimit -v"), std::string::npos) << output;
}
#endif

// Off a terminal (as here): a line per phase; --quiet, before or after the subcommand: none.
TEST(CliConventions, ProgressLinesOffATerminalAndQuiet) {
    const fs::path out = tempDir() / "progress";
    Result r = run("render" + kTiny + "--out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* phase : {"loading the scene\n", "building sahbvh8\n", "rendering 16x12\n"})
        EXPECT_NE(r.output.find(phase), std::string::npos) << phase << r.output;
    for (const std::string quiet : {"--quiet render", "render --quiet"}) {
        r = run(quiet + kTiny + "--out " + out.string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_EQ(r.output.find("rendering 16x12"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("N_IT"), std::string::npos) << r.output;  // results stay
    }
}
