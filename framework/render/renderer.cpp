#include "framework/render/renderer.h"

#include "framework/config/common_keys.h"
#include "framework/render/pixel_sampler.h"
#include "framework/render/render_keys.h"
#include "framework/scene/surface_point.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>

namespace bvhlab {
namespace {

constexpr int kTileSize = 16;

// A light as the renderer uses it: intensity already multiplied by the squared distance
// to the scene centre, so irradiance = intensity / d^2.
struct ShadingLight {
    Vec3 position;
    Vec3 intensity;
};

// One path of the current wavefront of a tile.
struct PathState {
    Ray ray;
    Vec3 throughput;
    uint32_t pixel;
};

// A shadow ray and the radiance it carries to its pixel if unoccluded.
struct ShadowQuery {
    Ray ray;
    Vec3 radiance;
    uint32_t pixel;
};

// Per-thread scratch and statistics, reused across tiles: nothing is allocated per ray.
struct ThreadState {
    std::vector<PathState> paths, nextPaths;
    std::vector<Ray> rays;  // the rays of one batch call
    std::vector<Hit> hits;
    std::vector<uint8_t> occluded;
    std::vector<Hit> countedHits;  // the counting calls' answers, apart from those shaded
    std::vector<uint8_t> countedOccluded;
    std::vector<RayCost> costs;
    std::vector<std::vector<ShadowQuery>> shadowsByLight;  // one batch per light
    RenderStats stats;
    double countingNanoseconds = 0.0;
};

class TileRenderer {
public:
    TileRenderer(const Scene& scene, const Accelerator& accel, const Camera& camera, const RenderSettings& settings,
                 const std::vector<ShadingLight>& lights, Framebuffer& fb)
        : scene_(scene),
          accel_(accel),
          camera_(camera),
          settings_(settings),
          lights_(lights),
          fb_(fb),
          counts_(settings.count && accel.hasCounters()) {}

    void renderTile(int x0, int y0, ThreadState& ts) const {
        const int x1 = std::min(x0 + kTileSize, fb_.width), y1 = std::min(y0 + kTileSize, fb_.height);
        for (int s = 0; s < settings_.samples; ++s) {
            ts.paths.clear();
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    const uint32_t pixel = uint32_t(fb_.index(x, y));
                    const glm::vec2 o = sampleOffset(pixel, s, settings_.samples);
                    ts.paths.push_back({camera_.generateRay(float(x) + o.x, float(y) + o.y),
                                        Vec3(1.0f / float(settings_.samples)), pixel});
                }
            for (int depth = 0; depth < settings_.depthLimit && !ts.paths.empty(); ++depth) {
                traceWavefront(ts, depth, s == 0);
                std::swap(ts.paths, ts.nextPaths);
            }
        }
    }

private:
    using Clock = std::chrono::steady_clock;

    void traceWavefront(ThreadState& ts, int depth, bool firstSample) const {
        ts.nextPaths.clear();
        ts.shadowsByLight.resize(lights_.size());
        for (std::vector<ShadowQuery>& shadows : ts.shadowsByLight) shadows.clear();
        const size_t n = ts.paths.size();
        ts.rays.resize(n);
        for (size_t i = 0; i < n; ++i) ts.rays[i] = ts.paths[i].ray;
        ts.hits.resize(n);
        // Closest hits of the whole wavefront first: one batch call, timed as a block. The camera's
        // rays of a tile, and their shadow rays towards one light, are coherent; the rays that
        // bounce off mirrors, and their shadow rays, may go anywhere.
        const RayCoherence coherence = depth == 0 ? RayCoherence::Coherent : RayCoherence::Incoherent;
        traceBatch(ts, ts.stats.primary, std::span(ts.hits), ts.countedHits, coherence);
        if (counts_)
            for (size_t i = 0; i < n; ++i) recordCost(ts.paths[i].pixel, ts.costs[i]);

        for (size_t i = 0; i < n; ++i) shade(ts, ts.paths[i], ts.hits[i], depth, firstSample);
        traceShadows(ts, coherence);
    }

    void query(std::span<const Ray> rays, std::span<Hit> hits, QueryCounters& counters, std::span<RayCost> costs,
               RayCoherence coherence) const {
        accel_.findNearestBatch(rays, hits, counters, costs, coherence);
    }
    void query(std::span<const Ray> rays, std::span<uint8_t> occluded, QueryCounters& counters,
               std::span<RayCost> costs, RayCoherence coherence) const {
        accel_.isOccludedBatch(rays, occluded, counters, costs, coherence);
    }

    // One batch of ts.rays: a timed call with counting off, whose answers are shaded; then, when
    // the render counts, an untimed call with counting on into answers of its own, for N_IT,
    // N_TR and each ray's cost in ts.costs (a structure that counts nothing would leave numbers
    // that are not its work).
    template <typename Answer>
    void traceBatch(ThreadState& ts, QueryStats& stats, std::span<Answer> answers, std::vector<Answer>& counted,
                    RayCoherence coherence) const {
        QueryCounters timed{.counting = false};
        const auto start = Clock::now();
        query(ts.rays, answers, timed, {}, coherence);
        const auto end = Clock::now();
        stats.queryNanoseconds += std::chrono::duration<double, std::nano>(end - start).count();
        stats.counters.queries += ts.rays.size();
        if (!counts_) return;
        QueryCounters work;
        counted.resize(ts.rays.size());
        ts.costs.resize(ts.rays.size());
        query(ts.rays, std::span(counted), work, ts.costs, coherence);
        stats.counters.addWork(work);
        ts.countingNanoseconds += std::chrono::duration<double, std::nano>(Clock::now() - end).count();
    }

    void recordCost(uint32_t pixel, const RayCost& cost) const {
        fb_.traversalSteps[pixel] += float(cost.traversalSteps);
        fb_.intersectionTests[pixel] += float(cost.intersectionTests);
    }

    void shade(ThreadState& ts, const PathState& path, const Hit& hit, int depth, bool firstSample) const {
        if (!hit.found()) {
            fb_.color[path.pixel] += path.throughput * settings_.background;
            return;
        }
        const SurfacePoint surface = surfaceAt(scene_, path.ray, hit);
        const Vec3& p = surface.position;
        const Vec3& ng = surface.geometricNormal;
        const Vec3& ns = surface.shadingNormal;
        if (depth == 0 && firstSample) {
            fb_.depth[path.pixel] = hit.t * glm::length(path.ray.dir);
            fb_.primitive[path.pixel] = hit.primitive;
            fb_.normal[path.pixel] = ns;
        }

        const Material& material = scene_.materials[scene_.materialOf(hit.primitive)];
        const Vec3 diffuse = path.throughput * material.diffuse * (1.0f - material.mirror);
        fb_.color[path.pixel] += diffuse * settings_.ambient;
        const Vec3 origin = surface.originAbove();
        for (size_t l = 0; l < lights_.size(); ++l) {
            const ShadingLight& light = lights_[l];
            const Vec3 toLight = light.position - p;
            const float distance2 = glm::dot(toLight, toLight);
            const float cosine = glm::dot(ns, toLight) / std::sqrt(distance2);
            if (cosine <= 0.0f || glm::dot(ng, toLight) <= 0.0f) {
                ++ts.stats.shadowRaysSkippedBackfacing;
                continue;
            }
            const Vec3 radiance = diffuse * light.intensity * (cosine / distance2);
            if (!settings_.shadows) {
                ++ts.stats.shadowRaysSkippedDisabled;
                fb_.color[path.pixel] += radiance;
                continue;
            }
            // The ray ends just short of the light: t = 1 is the light itself.
            ts.shadowsByLight[l].push_back(
                {Ray{origin, light.position - origin, 0.0f, 1.0f - 1e-5f}, radiance, path.pixel});
        }

        if (material.mirror > 0.0f) {
            if (depth + 1 < settings_.depthLimit) {
                const Vec3 reflected = glm::reflect(path.ray.dir, ns);
                ts.nextPaths.push_back(
                    {Ray{origin, reflected, 0.0f, kInfinity}, path.throughput * material.mirror, path.pixel});
            } else {
                ++ts.stats.bouncesSkipped;
            }
        }
    }

    // The shadow rays of the wavefront, one batch per light (rays towards one point). A pixel
    // has one path per wavefront, so it still receives its lights' radiance in light order.
    void traceShadows(ThreadState& ts, RayCoherence coherence) const {
        QueryStats& shadow = ts.stats.shadow;
        for (const std::vector<ShadowQuery>& queries : ts.shadowsByLight) {
            const size_t n = queries.size();
            ts.rays.resize(n);
            for (size_t i = 0; i < n; ++i) ts.rays[i] = queries[i].ray;
            ts.occluded.resize(n);
            traceBatch(ts, shadow, std::span(ts.occluded), ts.countedOccluded, coherence);
            for (size_t i = 0; i < n; ++i) {
                if (counts_) recordCost(queries[i].pixel, ts.costs[i]);
                // Unoccluded rays carry their radiance; occluded ones add nothing.
                if (!ts.occluded[i]) fb_.color[queries[i].pixel] += queries[i].radiance;
            }
        }
    }

    const Scene& scene_;
    const Accelerator& accel_;
    const Camera& camera_;
    const RenderSettings& settings_;
    const std::vector<ShadingLight>& lights_;
    Framebuffer& fb_;
    const bool counts_;  // the counting calls run
};

}  // namespace

RenderSettings RenderSettings::fromEnv(const Env& env, const Scene& scene, const CameraSpec& camera) {
    RenderSettings s;
    s.samples = env.get(keys::SetRayTracing::cntSamples);
    s.depthLimit = env.get(keys::SetRayTracing::depthLimit);
    s.shadows = env.get(keys::SetRayTracing::shadows);
    s.threads = env.get(keys::SetRayTracing::threads);
    s.ambient = env.get(keys::Render::ambient);
    if (const auto bg = env.get(keys::Scene::background))
        s.background = *bg;
    else if (scene.background)
        s.background = *scene.background;

    const std::vector<Vec3> positions = env.get(keys::Lights::positions);
    if (!positions.empty()) {
        for (const Vec3& p : positions) s.lights.push_back({p, Vec3(env.get(keys::Lights::intensity))});
    } else if (!scene.lights.empty()) {
        s.lights = scene.lights;
    } else {
        // A light above and to the right of the eye, so shadows fall visibly behind objects.
        const Vec3 forward = glm::normalize(camera.at - camera.from);
        const Vec3 right = glm::normalize(glm::cross(forward, camera.up));
        const float radius = 0.5f * glm::length(scene.bounds.diagonal());
        s.lights.push_back({camera.from + radius * (0.6f * right + 0.8f * glm::normalize(camera.up)), Vec3(1.0f)});
    }
    return s;
}

size_t tileCount(int width, int height) {
    return size_t((width + kTileSize - 1) / kTileSize) * size_t((height + kTileSize - 1) / kTileSize);
}

RenderStats render(const Scene& scene, const Accelerator& accel, const Camera& camera, const RenderSettings& settings,
                   Framebuffer& fb, const TileDone& onTile) {
    std::vector<ShadingLight> lights;
    const Vec3 center = scene.bounds.isEmpty() ? Vec3(0.0f) : scene.bounds.center();
    for (const PointLight& light : settings.lights) {
        const Vec3 d = light.position - center;
        lights.push_back({light.position, light.intensity * std::max(glm::dot(d, d), 1e-30f)});
    }

    const int threads = settings.threads > 0 ? settings.threads : tbb::info::default_concurrency();
    const int tilesX = (fb.width + kTileSize - 1) / kTileSize, tilesY = (fb.height + kTileSize - 1) / kTileSize;
    TileRenderer renderer(scene, accel, camera, settings, lights, fb);
    tbb::enumerable_thread_specific<ThreadState> states;

    const auto start = std::chrono::steady_clock::now();
    tbb::task_arena arena(threads);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, tilesX * tilesY, 1), [&](const tbb::blocked_range<int>& range) {
            ThreadState& ts = states.local();
            for (int tile = range.begin(); tile < range.end(); ++tile) {
                const uint64_t before = ts.stats.primary.counters.queries + ts.stats.shadow.counters.queries;
                renderer.renderTile(tile % tilesX * kTileSize, tile / tilesX * kTileSize, ts);
                if (onTile) onTile(ts.stats.primary.counters.queries + ts.stats.shadow.counters.queries - before);
            }
        });
    });

    RenderStats total;
    total.renderMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    total.threads = threads;
    double countingNanoseconds = 0.0;
    for (const ThreadState& ts : states) {
        countingNanoseconds += ts.countingNanoseconds;
        total.primary.counters += ts.stats.primary.counters;
        total.primary.queryNanoseconds += ts.stats.primary.queryNanoseconds;
        total.shadow.counters += ts.stats.shadow.counters;
        total.shadow.queryNanoseconds += ts.stats.shadow.queryNanoseconds;
        total.shadowRaysSkippedDisabled += ts.stats.shadowRaysSkippedDisabled;
        total.shadowRaysSkippedBackfacing += ts.stats.shadowRaysSkippedBackfacing;
        total.bouncesSkipped += ts.stats.bouncesSkipped;
    }
    if (!states.empty()) total.renderMs -= countingNanoseconds * 1e-6 / double(states.size());
    return total;
}

}  // namespace bvhlab
