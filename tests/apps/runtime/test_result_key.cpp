// The result key (apps/runtime/result_key.h): a structure's part holds its own keys and no other
// structure's, the scene's part the file's content and the rest of the env, the program's part
// this process's files; a change names the part and the value; a stored result is kept only
// under the same key.
#include "apps/runtime/app_keys.h"
#include "apps/runtime/program_keys.h"
#include "apps/runtime/result_key.h"
#include "tests/support/scratch_dir.h"

#include <gtest/gtest.h>

#include <fstream>

using namespace bvhlab;
using nlohmann::json;

namespace {

Env envWith(const std::vector<std::string>& overrides) {
    Env env(programKeys());
    for (const std::string& o : overrides) env.setOverride(o);
    return env;
}

}  // namespace

TEST(ResultKey, AStructureHoldsOnlyTheKeysItReads) {
    const Env env = envWith({"BVH::maxLeaf=3", "Embree::quality=high"});
    const json bvh = structureKey("sahbvh", env);
    EXPECT_EQ(bvh["keys"]["BVH::maxLeaf"], "3");
    EXPECT_FALSE(bvh["keys"].contains("Embree::quality")) << bvh.dump();
    EXPECT_TRUE(bvh["plugin"].is_null());
    const json embree = structureKey("embree", env);
    EXPECT_EQ(embree["keys"]["Embree::quality"], "high");
    EXPECT_FALSE(embree["keys"].contains("BVH::maxLeaf")) << embree.dump();
}

TEST(ResultKey, TheSceneIsItsFilesContentAndTheRestOfTheEnv) {
    const std::filesystem::path dir = test::scratchDir("result_key");
    std::ofstream(dir / "a.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    Env env = envWith({"Scene::dir=" + dir.string(), "Scene::file=a.obj", "Camera::width=64", "BVH::maxLeaf=3"});
    const json before = sceneKey(env);
    EXPECT_EQ(before["file"]["name"], "a.obj");
    EXPECT_EQ(before["settings"]["Camera::width"], "64");
    for (const char* notTheScenes : {"BVH::maxLeaf", "Embree::quality", "Scene::file", "Scene::dir", "ASDS::type",
                                     "Output::exr", "Scene::cacheDir"})
        EXPECT_FALSE(before["settings"].contains(notTheScenes)) << notTheScenes;
    EXPECT_EQ(sceneKey(envWith({})), sceneKey(envWith({"BVH::maxLeaf=3"})));

    // The same content elsewhere is the same scene; another camera is not.
    std::filesystem::create_directories(dir / "moved");
    std::filesystem::copy_file(dir / "a.obj", dir / "moved" / "a.obj");
    EXPECT_EQ(sceneKey(envWith({"Scene::dir=" + (dir / "moved").string(), "Scene::file=a.obj", "Camera::width=64"})),
              before);
    const std::vector<std::string> changes = resultKeyChanges(
        {{"scene", before}},
        {{"scene", sceneKey(envWith({"Scene::dir=" + dir.string(), "Scene::file=a.obj", "Camera::width=32"}))}});
    EXPECT_EQ(changes, std::vector<std::string>{"scene Camera::width: 64 -> 32"});
}

// The frame decides an animated scene's figures, and nothing of a still one's.
TEST(ResultKey, TheFrameIsPartOfAnAnimatedScene) {
    const std::filesystem::path dir = test::scratchDir("result_key_frame");
    std::ofstream(dir / "a.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(dir / "b.aff") << "p 3\n0 0 0\n1 0 0\n0 1 0\na 0 1 3\n";
    const auto key = [&](const char* file, const char* frame) {
        return sceneKey(envWith(
            {"Scene::dir=" + dir.string(), std::string("Scene::file=") + file, std::string("Scene::frame=") + frame}));
    };
    EXPECT_EQ(resultKeyChanges({{"scene", key("b.aff", "0")}}, {{"scene", key("b.aff", "2")}}),
              std::vector<std::string>{"scene Scene::frame: 0 -> 2"});
    EXPECT_EQ(key("a.obj", "0"), key("a.obj", "2"));
    EXPECT_FALSE(key("a.obj", "2")["settings"].contains("Scene::frame"));
}

// An AFF scene is also the files it includes: the same root over another include is another scene.
TEST(ResultKey, AnAffScenesIncludesArePartOfIt) {
    const std::filesystem::path dir = test::scratchDir("result_key_includes");
    json keys[2];
    for (const int k : {0, 1}) {
        const std::filesystem::path folder = dir / std::to_string(k);
        std::filesystem::create_directories(folder / "sub");
        std::ofstream(folder / "root.aff") << "i 0 sub/part.aff\n";
        std::ofstream(folder / "sub" / "part.aff") << "p 3\n0 0 0\n1 0 0\n0 1 " << k << "\n";
        keys[k] = sceneKey(envWith({"Scene::dir=" + folder.string(), "Scene::file=root.aff"}));
    }
    ASSERT_TRUE(keys[0]["file"]["includes"].contains("sub/part.aff")) << keys[0].dump();
    const std::vector<std::string> changes = resultKeyChanges({{"scene", keys[0]}}, {{"scene", keys[1]}});
    ASSERT_EQ(changes.size(), 1u);
    EXPECT_TRUE(changes[0].starts_with("scene file includes sub/part.aff: 22-")) << changes[0];
}

TEST(ResultKey, TheProgramIsThisProcesssFiles) {
    const json& program = programIdentity();
    EXPECT_FALSE(program["commit"].get<std::string>().empty());
    ASSERT_TRUE(program["files"].contains("bvhlab")) << program.dump();
    EXPECT_NE(program["files"]["bvhlab"].get<std::string>().find('-'), std::string::npos);  // SIZE-CRC32
    EXPECT_EQ(&programIdentity(), &program);                                                // read once
}

TEST(ResultKey, ChangesNameThePartAndTheValue) {
    const json before = {{"program", {{"commit", "abc"}, {"files", {{"bvhlab", "10-0000aaaa"}}}}},
                         {"structure",
                          {{"accel", "scan"},
                           {"keys", {{"Scan::passes", "1"}}},
                           {"plugin", {{"file", "scan.so"}, {"crc32", "11111111"}}}}},
                         {"measurement", {{"passes", 3}}}};
    json after = before;
    EXPECT_TRUE(resultKeyChanges(before, after).empty());
    after["program"]["files"]["bvhlab"] = "10-0000bbbb";
    after["structure"]["keys"]["Scan::passes"] = "2";
    after["structure"]["plugin"]["crc32"] = "22222222";
    after["measurement"]["passes"] = 5;
    EXPECT_EQ(
        resultKeyChanges(before, after),
        (std::vector<std::string>{"measurement passes: 3 -> 5", "plugin crc32: 11111111 -> 22222222",
                                  "program bvhlab: 10-0000aaaa -> 10-0000bbbb", "structure Scan::passes: 1 -> 2"}));
}

TEST(ResultKey, AStoredResultIsKeptOnlyUnderTheSameKey) {
    const std::filesystem::path dir = test::scratchDir("result_key");
    const json key = {{"structure", {{"accel", "sahbvh"}, {"keys", {{"BVH::maxLeaf", "2"}}}}}};
    EXPECT_EQ(checkStoredResult(dir / "none.json", key).why, "new");
    std::ofstream(dir / "old.json") << json{{"result", 1}}.dump();
    EXPECT_FALSE(checkStoredResult(dir / "old.json", key).keep);
    std::ofstream(dir / "same.json") << json{{"result", 1}, {"result_key", key}}.dump();
    EXPECT_TRUE(checkStoredResult(dir / "same.json", key).keep);
    json other = key;
    other["structure"]["keys"]["BVH::maxLeaf"] = "3";
    const StoredResult changed = checkStoredResult(dir / "same.json", other);
    EXPECT_FALSE(changed.keep);
    EXPECT_EQ(changed.why, "structure BVH::maxLeaf: 2 -> 3");

    ResumeCount count;
    for (const char* file : {"same.json", "same.json", "none.json"}) count.add(checkStoredResult(dir / file, key));
    count.add(changed);
    EXPECT_EQ(count.kept(), 2u);
    EXPECT_EQ(count.toMeasure(), 2u);
    EXPECT_EQ(count.summary("jobs", "run"),
              "2 jobs kept from an earlier run (same result key); 2 to run: 1 new; 1 "
              "because structure BVH::maxLeaf: 2 -> 3");
}
