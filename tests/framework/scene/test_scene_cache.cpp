// The binary scene cache: a scene survives the round trip field by field, the key follows the
// source's bytes, damaged or foreign entries are refused with a reason, never trusted, and
// readers racing writers of one entry (shards sharing the folder) see it whole or not at all.
#include "framework/core/error.h"
#include "framework/scene/procedural.h"
#include "framework/scene/scene_cache.h"
#include "tests/support/scratch_dir.h"

#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <mutex>
#include <thread>

using namespace bvhlab;
namespace fs = std::filesystem;

namespace {

fs::path cacheScratchDir() { return test::scratchDir("scene_cache"); }

Scene richScene() {
    Scene scene = makeDefaultScene();  // several materials, a camera and a light
    scene.name = "rich";
    scene.normals.assign(scene.positions.size(), Vec3(0, 1, 0));
    scene.background = Vec3(0.1f, 0.2f, 0.3f);
    scene.spheres = {{Vec3(1, 2, 3), 0.5f}, {Vec3(0), 0.0f}};  // the second degenerate
    scene.sphereMaterialIds = {1, 0};
    scene.cones = {{Vec3(0), 1.0f, Vec3(0, 0, 2), -0.5f}, {Vec3(0), -1.0f, Vec3(0, 1, 0), -0.25f}};
    scene.coneMaterialIds = {0, 1};
    scene.materials.back().shine = 20.0f;
    scene.materials.back().transmission = 0.5f;
    scene.materials.back().ior = 1.5f;
    scene.report.warnings = {"first warning", "", "third, with a\nnewline"};
    scene.indices.push_back({0, 0, 0});  // one degenerate triangle
    if (!scene.materialIds.empty()) scene.materialIds.push_back(0);
    scene.finalize();
    return scene;
}

}  // namespace

TEST(SceneCache, RoundTripKeepsEveryField) {
    const Scene scene = richScene();
    const fs::path source = cacheScratchDir() / "rich.obj";
    std::ofstream(source) << "source bytes";
    const SceneCacheKey key = sceneCacheKey(source);
    EXPECT_EQ(key.size, 12u);
    const fs::path file = cacheScratchDir() / key.cacheFileName();
    writeSceneCache(file, key, scene);

    std::string why;
    const std::optional<Scene> back = readSceneCache(file, key, source, &why);
    ASSERT_TRUE(back) << why;
    EXPECT_EQ(back->name, "rich");
    EXPECT_EQ(back->source, source);
    EXPECT_EQ(back->positions, scene.positions);
    EXPECT_EQ(back->normals, scene.normals);
    EXPECT_EQ(back->indices, scene.indices);
    EXPECT_EQ(back->materialIds, scene.materialIds);
    ASSERT_EQ(back->materials.size(), scene.materials.size());
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        EXPECT_EQ(back->materials[i].diffuse, scene.materials[i].diffuse);
        EXPECT_EQ(back->materials[i].mirror, scene.materials[i].mirror);
    }
    ASSERT_EQ(back->lights.size(), scene.lights.size());
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        EXPECT_EQ(back->lights[i].position, scene.lights[i].position);
        EXPECT_EQ(back->lights[i].intensity, scene.lights[i].intensity);
    }
    ASSERT_EQ(back->camera.has_value(), scene.camera.has_value());
    if (scene.camera) {
        EXPECT_EQ(back->camera->from, scene.camera->from);
        EXPECT_EQ(back->camera->at, scene.camera->at);
        EXPECT_EQ(back->camera->up, scene.camera->up);
        EXPECT_EQ(back->camera->fovyDegrees, scene.camera->fovyDegrees);
        EXPECT_EQ(back->camera->width, scene.camera->width);
        EXPECT_EQ(back->camera->height, scene.camera->height);
    }
    EXPECT_EQ(back->background, scene.background);
    EXPECT_EQ(back->report.degenerateTriangles, 1u);
    ASSERT_EQ(back->spheres.size(), 2u);
    EXPECT_EQ(back->spheres[0].centre, scene.spheres[0].centre);
    EXPECT_EQ(back->spheres[0].radius, scene.spheres[0].radius);
    ASSERT_EQ(back->cones.size(), 2u);
    EXPECT_EQ(back->cones[1].apex, scene.cones[1].apex);
    EXPECT_EQ(back->cones[1].apexRadius, scene.cones[1].apexRadius);
    EXPECT_EQ(back->sphereMaterialIds, scene.sphereMaterialIds);
    EXPECT_EQ(back->coneMaterialIds, scene.coneMaterialIds);
    EXPECT_EQ(back->report.degenerateSpheres, 1u);
    EXPECT_EQ(back->report.degenerateCones, 1u);
    ASSERT_EQ(back->materials.size(), scene.materials.size());
    EXPECT_EQ(back->materials.back().shine, 20.0f);
    EXPECT_EQ(back->materials.back().transmission, 0.5f);
    EXPECT_EQ(back->materials.back().ior, 1.5f);
    EXPECT_EQ(back->report.warnings, scene.report.warnings);
    EXPECT_EQ(back->validPrimitives, scene.validPrimitives);
    EXPECT_EQ(back->triangles.size(), scene.triangles.size());
}

TEST(SceneCache, KeyFollowsTheBytes) {
    const fs::path a = cacheScratchDir() / "same.obj", b = cacheScratchDir() / "same.ply";
    std::ofstream(a) << "v 0 0 0\n";
    std::ofstream(b) << "v 0 0 0\n";
    const SceneCacheKey ka = sceneCacheKey(a), kb = sceneCacheKey(b);
    EXPECT_EQ(ka.crc32, kb.crc32);
    EXPECT_NE(ka.cacheFileName(), kb.cacheFileName());  // another reader: another entry
    std::ofstream(a) << "v 0 0 1\n";
    EXPECT_NE(sceneCacheKey(a).cacheFileName(), ka.cacheFileName());
    EXPECT_NE(ka.cacheFileName().find(".v" + std::to_string(kSceneCacheVersion) + "."), std::string::npos);
}

TEST(SceneCache, DamagedOrForeignEntriesAreRefused) {
    const Scene scene = richScene();
    const fs::path source = cacheScratchDir() / "damaged.obj";
    std::ofstream(source) << "abc";
    const SceneCacheKey key = sceneCacheKey(source);
    const fs::path file = cacheScratchDir() / key.cacheFileName();
    auto reason = [&]() {
        std::string why;
        EXPECT_FALSE(readSceneCache(file, key, source, &why));
        return why;
    };
    writeSceneCache(file, key, scene);
    const uint64_t size = fs::file_size(file);

    fs::resize_file(file, size - 1);
    EXPECT_EQ(reason(), "truncated");
    fs::resize_file(file, 10);
    EXPECT_EQ(reason(), "truncated");

    writeSceneCache(file, key, scene);
    {
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(std::streamoff(size / 2));
        f.put('\x7f');
    }
    EXPECT_NE(reason().find("checksum"), std::string::npos);

    writeSceneCache(file, key, scene);
    SceneCacheKey other = key;
    other.crc32 ^= 1;
    std::string why;
    EXPECT_FALSE(readSceneCache(file, other, source, &why));
    EXPECT_EQ(why, "written for other source bytes");

    std::ofstream(file, std::ios::trunc) << std::string(400, 'x');
    EXPECT_EQ(reason(), "not a scene cache file");
    fs::remove(file);
    EXPECT_EQ(reason(), "missing");

    // loadSceneCached parses and rewrites past a bad entry.
    const fs::path obj = cacheScratchDir() / "tri.obj";
    std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const fs::path cacheDir = cacheScratchDir() / "cache";
    fs::remove_all(cacheDir);
    CachedScene first = loadSceneCached(obj, cacheDir);
    EXPECT_FALSE(first.fromCache);
    EXPECT_TRUE(first.note.empty()) << first.note;
    std::ofstream(first.cacheFile, std::ios::trunc) << "garbage";
    CachedScene second = loadSceneCached(obj, cacheDir);
    EXPECT_FALSE(second.fromCache);
    EXPECT_NE(second.note.find("ignored cache entry"), std::string::npos) << second.note;
    CachedScene third = loadSceneCached(obj, cacheDir);
    EXPECT_TRUE(third.fromCache);
    EXPECT_EQ(third.scene.triangleCount(), 1u);
    EXPECT_EQ(third.scene.name, "tri");
}

TEST(SceneCache, AnEntryWithNothingToRenderIsRefusedAsTheFileWouldBe) {
    // An entry for these bytes that holds no triangles (written by hand, or before loadScene
    // refused such scenes) must not give the empty scene that loading the file refuses.
    const fs::path source = cacheScratchDir() / "hollow.obj";
    std::ofstream(source) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const SceneCacheKey key = sceneCacheKey(source);
    const fs::path cacheDir = cacheScratchDir() / "hollow_cache";
    fs::create_directories(cacheDir);
    Scene empty;
    empty.name = "hollow";
    empty.finalize();
    writeSceneCache(cacheDir / key.cacheFileName(), key, empty);
    try {
        loadSceneCached(source, cacheDir);
        ADD_FAILURE() << "no InputError thrown";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("hollow.obj: nothing to render"), std::string::npos) << e.what();
    }
}

TEST(SceneCache, ReadersRacingWritersOfOneEntrySeeItWholeOrMissing) {
    // Two writers rewrite the entry over and over (as shards that parsed the same scene store
    // it) while two readers read it: a read gives the whole scene, or "missing" before the first
    // rename, never a part of one; no temporary file is left.
    const Scene scene = richScene();
    const fs::path source = cacheScratchDir() / "raced.obj";
    std::ofstream(source) << "raced source";
    const SceneCacheKey key = sceneCacheKey(source);
    const fs::path dir = cacheScratchDir() / "raced_cache";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path file = dir / key.cacheFileName();

    std::atomic<int> writing{2}, whole{0};
    std::mutex mutex;
    std::vector<std::string> wrong;
    auto read = [&] {
        std::string why;
        const std::optional<Scene> back = readSceneCache(file, key, source, &why);
        if (back && back->positions == scene.positions && back->indices == scene.indices) {
            ++whole;
        } else if (back || why != "missing") {
            const std::lock_guard lock(mutex);
            wrong.push_back(back ? "another scene" : why);
        }
    };
    std::vector<std::thread> threads;
    for (int w = 0; w < 2; ++w)
        threads.emplace_back([&] {
            for (int i = 0; i < 30; ++i) writeSceneCache(file, key, scene);
            --writing;
        });
    for (int r = 0; r < 2; ++r)
        threads.emplace_back([&] {
            while (writing > 0) read();
            read();  // after the last rename
        });
    for (std::thread& t : threads) t.join();
    EXPECT_TRUE(wrong.empty()) << wrong.size() << " bad reads, the first: " << wrong.front();
    EXPECT_GE(whole, 2);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}
