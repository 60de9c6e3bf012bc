// The ray sets the bench traces, made once per scene so every structure answers the same
// rays: primary rays through pixel centres, shadow rays from their hits to each light, and
// incoherent rays (cosine-distributed bounces from the hits, as ambient occlusion casts them).
#pragma once

#include "framework/config/env.h"
#include "framework/core/accelerator.h"
#include "framework/render/camera.h"

#include <vector>

namespace bvhlab {

struct RaySets {
    std::vector<Ray> primary;
    std::vector<Ray> shadow;      // any-hit queries
    std::vector<Ray> incoherent;  // any-hit queries of length aoRadius
};

// How each set is asked, in RaySets' order: shadow and incoherent rays are any-hit queries;
// primary rays (row by row) and shadow rays (from neighbouring pixels' hits towards the lights)
// are coherent batches, the bounces are not.
struct RaySetQuery {
    const char* kind;
    bool anyHit;
    RayCoherence coherence;
};
inline constexpr RaySetQuery kRaySetQueries[] = {{"primary", false, RayCoherence::Coherent},
                                                 {"shadow", true, RayCoherence::Coherent},
                                                 {"incoherent", true, RayCoherence::Incoherent}};

// `reference` answers the primary rays to find the surfaces the other rays start from.
// `aoRadiusFraction` is the incoherent rays' length relative to the scene's bounding diagonal.
RaySets makeRaySets(const Scene& scene, const Camera& camera, const std::vector<PointLight>& lights,
                    const Accelerator& reference, float aoRadiusFraction = 0.1f, uint32_t seed = 1);

// The ray sets of the scene's camera and lights as env resolves them (its size, the scene's own
// view), made from the reference's hits: what `bench`, `tradeoff` and `rays` trace and write.
RaySets sceneRaySets(const Scene& scene, const Env& env, const Accelerator& reference);

// One set of sceneRaySets, `kind` primary, shadow or incoherent (else InputError), with Embree
// as the reference: what `bvhlab rays` writes and bvhlab.rays (Python) returns.
std::vector<Ray> benchRays(const Scene& scene, const Env& env, const std::string& kind);

}  // namespace bvhlab
