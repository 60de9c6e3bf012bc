// Reading the scene an env names, with what the load met reported on stderr.
#pragma once

#include "framework/config/env.h"
#include "framework/scene/animated_scene.h"
#include "framework/scene/scene.h"

#include <filesystem>

namespace bvhlab {

// How loadSceneFor got its scene.
struct SceneLoadInfo {
    bool fromCache = false;           // read from the scene cache, not parsed
    std::filesystem::path cacheFile;  // the cache entry read or written; empty when the cache was not used
    double ms = 0.0;                  // load time (hashing, reading or parsing, finalize)
};

// The file Scene::file names, in Scene::dir unless absolute; empty for the embedded scene.
// Throws InputError naming the file and how to set Scene::dir when a relative one is not there.
std::filesystem::path sceneFileOf(const Env& env);

// The scene of Scene::file (in Scene::dir; --scene sets it absolute), else the embedded default; load problems
// (degenerate primitives, NFF spheres and cones, warnings) are reported on stderr. With `useCache`
// a scene file is read from / stored into the binary cache in Scene::cacheDir (empty = no cache; see
// framework/scene/scene_cache.h); only `bvhlab batch` uses it (docs/batch.md), every other
// command parses its scenes each time and writes nothing outside its outputs. An animated scene
// (.aff, never cached: it spans files) is the one at the frame Scene::frame names, with its camera
// and lights then; a frame past its last is an InputError, and a still scene ignores the key (a
// warning of the run unless it is 0).
Scene loadSceneFor(const Env& env, bool useCache = false, SceneLoadInfo* info = nullptr);

// The same with what moves in it, for a caller that moves it to other times (Python): a still
// scene comes as an animation of one frame at time 0 in which nothing moves.
AnimatedScene loadAnimatedSceneFor(const Env& env);

}  // namespace bvhlab
