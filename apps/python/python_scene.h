// A scene as Python holds it: the scene with what moves in it and the env it was loaded with (its
// camera and lights, for bvhlab.rays), shared by every accelerator built over it, which keeps
// views of its arrays.
#pragma once

#include "framework/config/env.h"
#include "framework/scene/animated_scene.h"

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

namespace bvhlab {

struct PythonScene {
    AnimatedScene animated;  // a still scene: one frame at time 0 in which nothing moves
    Env env;
    // How often set_time moved primitives: a structure built or updated at another count answers
    // for positions the scene no longer has.
    uint64_t moves = 0;

    Scene& scene() { return animated.scene; }
    const Scene& scene() const { return animated.scene; }
};

// {"BVH::bins": 32, ...} as -D assignments ("BVH::bins=32"): booleans as true/false, numbers and
// strings as Python writes them. Throws InputError for a key that is not a string.
std::vector<std::string> envAssignments(const pybind11::object& env);

}  // namespace bvhlab
