// A scene as Python holds it: the scene and the env it was loaded with (its camera and lights,
// for bvhlab.rays), shared by every accelerator built over it, which keeps views of its arrays.
#pragma once

#include "framework/config/env.h"
#include "framework/scene/scene.h"

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

namespace bvhlab {

struct PythonScene {
    Scene scene;
    Env env;
};

// {"BVH::bins": 32, ...} as -D assignments ("BVH::bins=32"): booleans as true/false, numbers and
// strings as Python writes them. Throws InputError for a key that is not a string.
std::vector<std::string> envAssignments(const pybind11::object& env);

}  // namespace bvhlab
