// An accelerator as Python holds it: the structure, its build statistics, and the scene it was
// built over (its primitives, of which the structure keeps views, and the env it reads).
#pragma once

#include "apps/python/python_scene.h"
#include "framework/core/accelerator.h"

#include <memory>

namespace bvhlab {

struct PythonAccelerator {
    std::shared_ptr<PythonScene> scene;
    std::unique_ptr<Accelerator> accel;
    BuildStats stats;
    uint64_t sceneMoves = 0;  // the scene's PythonScene::moves when built or last updated
    // The primitives built over: all of them and a hash of the valid ones, for an update to see
    // that the valid ones changed at the same count (a moving triangle became degenerate).
    size_t primitives = 0;
    uint64_t validHash = 0;

    // The scene, which must not have moved since: else InputError saying to update or rebuild.
    const Scene& currentScene() const;
};

// The scene's env with `threads` (0: all hardware threads; else InputError below 0) and the
// dict's keys over it, as bvhlab.build and bvhlab.render read it.
Env envWith(const PythonScene& scene, const pybind11::object& env, int threads);

}  // namespace bvhlab
