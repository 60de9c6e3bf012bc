#include "apps/runtime/build_accelerator.h"

#include "accel/registry.h"
#include "apps/runtime/build_watch.h"
#include "framework/core/timed_build.h"

#include <fmt/core.h>

namespace bvhlab {

BuiltAccelerator buildAccelerator(const Scene& scene, const Env& env) {
    BuiltAccelerator built{createAccelerator(env), {}};
    {
        const BuildWatch watch(fmt::format("{} on {}", built.accel->name(), scene.name));
        built.stats = timedBuild(*built.accel, scene.primitives());
    }
    fmt::print(stderr, "{}: built over {} primitives in {:.1f} ms\n", built.accel->name(), built.stats.primitives,
               built.stats.buildMs);
    return built;
}

}  // namespace bvhlab
