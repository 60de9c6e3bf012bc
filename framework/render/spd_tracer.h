// The ray tracer of Eric Haines' Standard Procedural Databases (SPD_Readme.txt, "Testing
// Procedures"): eye rays at the corners of the pixels (the four corners averaged), Whitted
// recursion to a fixed tree depth with a reflection ray from every hit on a reflective or
// transmitting surface and a refraction ray (Snell's law) from every hit on a transmitting
// one, a shadow ray per light unless the normal faces away from it, Phong highlights. It counts the rays under
// Havran's names (havran_stats_grids.txt): invariants that every correct ray tracer reproduces
// whatever its acceleration structure.
#pragma once

#include "framework/core/accelerator.h"
#include "framework/render/framebuffer.h"
#include "framework/scene/scene.h"

#include <functional>

namespace bvhlab {

struct SpdRules {
    int maxDepth = 5;  // the eye ray is depth 1; rays of this depth spawn no further rays
    int threads = 0;   // 0 = all hardware threads
    // Opaque primitives are seen from both sides (SPD rule 2's exception: the teapot, whose
    // lid does not fit); otherwise every primitive is one-sided.
    bool twoSided = false;
};

// Havran's invariants, and what the rules let a scene skip.
struct SpdCounts {
    uint64_t primaryRays = 0;      // PrimaryRay
    uint64_t usedIntPrimRays = 0;  // UsedIntPrimRay: primary rays that hit
    uint64_t shadowRays = 0;       // ShadowRay
    uint64_t usedIntShadRays = 0;  // UsedIntShadRay: shadow rays that hit (the light is occluded)
    uint64_t secondaryRays = 0;    // SecondaryRay: reflection and refraction rays
    uint64_t usedIntSecRays = 0;   // UsedIntSecRay: secondary rays that hit

    uint64_t reflectionRays = 0, refractionRays = 0;  // the secondary rays by kind
    uint64_t totalInternalReflections = 0;            // refractions that became reflections only
    uint64_t shadowRaysSkippedBackfacing = 0;         // the normal faces away from the light
    uint64_t raysCutByDepth = 0;                      // reflection or refraction rays not spawned at maxDepth

    uint64_t allRays() const { return primaryRays + shadowRays + secondaryRays; }
    uint64_t intersRequired() const { return usedIntPrimRays + usedIntShadRays + usedIntSecRays; }
    SpdCounts& operator+=(const SpdCounts& o);
};

struct SpdResult {
    SpdCounts counts;
    QueryCounters closest;  // every closest-hit query (eye, reflection and refraction rays)
    QueryCounters shadow;   // every shadow query
    double traceMs = 0.0;   // wall time of the whole trace, build excluded
    int threads = 0;
};

// Called after each row of eye rays with the rays that row cast (for progress lines).
using SpdRowDone = std::function<void(uint64_t rays)>;

// Traces `scene` (its camera: required) with `accel` built over it. `framebuffer` must be the
// camera's resolution: each pixel gets the average of its four corner rays' colours, and its
// cost AOVs the average of theirs.
SpdResult traceSpd(const Scene& scene, const Accelerator& accel, const SpdRules& rules, Framebuffer& framebuffer,
                   const SpdRowDone& onRow = {});

}  // namespace bvhlab
