// Whitted-style rendering over tiles: primary rays, Lambert shading with a shadow ray per
// light, mirror bounces. Counts every query by kind and times the queries alone: each batch is
// timed with counting off, then counted by a second, untimed call on the same rays.
#pragma once

#include "framework/config/env.h"
#include "framework/core/accelerator.h"
#include "framework/render/camera.h"
#include "framework/render/framebuffer.h"

#include <functional>

namespace bvhlab {

struct RenderSettings {
    int samples = 1;
    int depthLimit = 1;
    bool shadows = true;
    int threads = 0;  // 0 = all hardware threads
    // The counting calls (N_IT, N_TR, the heat maps); off where only images and times are wanted.
    bool count = true;
    float ambient = 0.05f;
    Vec3 background{0.05f, 0.06f, 0.09f};
    std::vector<PointLight> lights;

    // Reads SetRayTracing::*, Render::*, Lights::* and Scene::background; lights and background
    // fall back to the scene's, then to defaults derived from the scene's size and camera.
    static RenderSettings fromEnv(const Env& env, const Scene& scene, const CameraSpec& camera);
};

// Query counts and the thread-time spent inside the accelerator for one kind of query.
struct QueryStats {
    QueryCounters counters;         // queries; N_IT, N_TR of the counting calls (none: 0)
    double queryNanoseconds = 0.0;  // of the timed calls, which count nothing; summed over threads

    double usPerQuery() const { return counters.queries ? queryNanoseconds * 1e-3 / double(counters.queries) : 0.0; }
};

struct RenderStats {
    QueryStats primary;  // closest-hit queries: camera rays and mirror bounces
    QueryStats shadow;   // any-hit queries toward the lights
    // Work skipped because the scene did not need it (see "no work a scene does not need").
    uint64_t shadowRaysSkippedDisabled = 0;    // shadows off, or no light
    uint64_t shadowRaysSkippedBackfacing = 0;  // light behind the surface (N·L <= 0)
    uint64_t bouncesSkipped = 0;               // hit surfaces that reflect when depthLimit ended the path
    // Wall time of the whole render, build excluded, less the counting calls: their thread time
    // over the threads that rendered (exact on one thread).
    double renderMs = 0.0;
    int threads = 0;
};

// Called from a render thread after each tile with the rays (queries) the tile traced; the
// callers draw progress lines with it.
using TileDone = std::function<void(uint64_t rays)>;

// The number of tiles a render of `width` x `height` pixels calls TileDone for.
size_t tileCount(int width, int height);

RenderStats render(const Scene& scene, const Accelerator& accel, const Camera& camera, const RenderSettings& settings,
                   Framebuffer& framebuffer, const TileDone& onTile = {});

}  // namespace bvhlab
