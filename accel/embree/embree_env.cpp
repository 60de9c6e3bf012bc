#include "accel/embree/embree_env.h"

namespace bvhlab {

void registerEmbreeKeys(EnvRegistry& r) {
    using T = EnvType;
    r.add({"Embree::quality", T::Choice, "medium",
           "Embree build quality: low (two-level, fastest build), medium (default), high (spatial splits)", 0, 0,
           {"low", "medium", "high"}});
    r.add({"Embree::robust", T::Bool, "false",
           "RTC_SCENE_FLAG_ROBUST: robust traversal, no optimisations that reduce arithmetic accuracy", 0, 0, {}});
    r.add({"Embree::threads", T::Int, "0",
           "Embree build threads; 0 = as SetRayTracing::threads. Process-wide: limits TBB while the device lives", 0,
           1024, {}});
}

}  // namespace bvhlab
