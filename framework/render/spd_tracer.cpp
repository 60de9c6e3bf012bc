#include "framework/render/spd_tracer.h"

#include "framework/core/error.h"
#include "framework/render/camera.h"
#include "framework/scene/surface_point.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <vector>

namespace bvhlab {

SpdCounts& SpdCounts::operator+=(const SpdCounts& o) {
    primaryRays += o.primaryRays;
    usedIntPrimRays += o.usedIntPrimRays;
    shadowRays += o.shadowRays;
    usedIntShadRays += o.usedIntShadRays;
    secondaryRays += o.secondaryRays;
    usedIntSecRays += o.usedIntSecRays;
    reflectionRays += o.reflectionRays;
    refractionRays += o.refractionRays;
    totalInternalReflections += o.totalInternalReflections;
    shadowRaysSkippedBackfacing += o.shadowRaysSkippedBackfacing;
    raysCutByDepth += o.raysCutByDepth;
    return *this;
}

namespace {

struct SpdThreadState {
    SpdResult result;
    // One row of eye rays, traced as one batch.
    std::vector<Ray> rays;
    std::vector<Hit> hits;
    std::vector<RayCost> costs;
};

// What one corner ray brings back to its pixels.
struct Sample {
    Vec3 color{0.0f};
    float steps = 0.0f, tests = 0.0f;
    float depth = kInfinity;
    uint32_t primitive = kInvalidPrimitive;
    Vec3 normal{0.0f};
};

class SpdTracer {
public:
    SpdTracer(const Scene& scene, const Accelerator& accel, const SpdRules& rules, Vec3 background)
        : scene_(scene), accel_(accel), rules_(rules), background_(background) {
        // SPD_Readme: "A simple formula for a relative intensity (i.e. between 0 and 1) for
        // each light is sqrt(# lights) / (# lights * 2)".
        const float n = float(scene.lights.size());
        lightIntensity_ = n > 0.0f ? std::sqrt(n) / (2.0f * n) : 0.0f;
    }

    // The eye ray `ray`, whose closest hit `hit` (Hit{} on a miss) a batch found at `cost`.
    Sample eyeRay(const Ray& ray, const Hit& hit, RayCost cost, SpdThreadState& ts) const {
        Sample sample;
        const QueryCounters before = total(ts);
        sample.color = shade(ray, hit, 1, ts, &sample);
        const QueryCounters after = total(ts);
        sample.steps = float(cost.traversalSteps + after.traversalSteps - before.traversalSteps);
        sample.tests = float(cost.intersectionTests + after.intersectionTests - before.intersectionTests);
        return sample;
    }

private:
    static QueryCounters total(const SpdThreadState& ts) {
        QueryCounters c = ts.result.closest;
        c += ts.result.shadow;
        return c;
    }

    // The colour seen along `ray`, a ray of tree depth `depth` (the eye ray is 1).
    Vec3 trace(const Ray& ray, int depth, SpdThreadState& ts, Sample* eye) const {
        Hit hit;
        accel_.findNearest(ray, hit, ts.result.closest);
        return shade(ray, hit, depth, ts, eye);
    }

    // The light of every point light that reaches `position` (normal `n`, seen from `view`),
    // each asked by a shadow ray from `shadowOrigin`.
    Vec3 directLight(const Vec3& position, const Vec3& n, const Vec3& view, const Material& material,
                     const Vec3& shadowOrigin, SpdThreadState& ts) const {
        SpdCounts& counts = ts.result.counts;
        Vec3 color{0.0f};
        for (const PointLight& light : scene_.lights) {
            const Vec3 toLight = light.position - position;
            const float cosine = glm::dot(n, toLight);
            // SPD rule 10: no shadow ray where the normal points away from the light.
            if (cosine <= 0.0f) {
                ++counts.shadowRaysSkippedBackfacing;
                continue;
            }
            ++counts.shadowRays;
            // t = 1 is the light itself.
            if (accel_.isOccluded({shadowOrigin, light.position - shadowOrigin, 0.0f, 1.0f - 1e-5f},
                                  ts.result.shadow)) {
                ++counts.usedIntShadRays;
                continue;
            }
            const Vec3 l = toLight / std::sqrt(glm::dot(toLight, toLight));
            const float diffuse = glm::dot(n, l);
            // Phong: the highlight around the mirror direction of the light, for reflective surfaces.
            const float highlight = material.mirror > 0.0f
                                        ? std::pow(std::max(0.0f, glm::dot(glm::reflect(-l, n), view)), material.shine)
                                        : 0.0f;
            color +=
                lightIntensity_ * (material.diffuse * diffuse + Vec3(material.mirror * highlight)) * light.intensity;
        }
        return color;
    }

    // The colour seen along `ray`, whose closest hit is `hit`.
    Vec3 shade(const Ray& ray, const Hit& hit, int depth, SpdThreadState& ts, Sample* eye) const {
        SpdCounts& counts = ts.result.counts;
        ++(depth == 1 ? counts.primaryRays : counts.secondaryRays);
        if (!hit.found()) return background_;
        ++(depth == 1 ? counts.usedIntPrimRays : counts.usedIntSecRays);

        const SurfacePoint surface = surfaceAt(scene_, ray, hit);
        const Material& material = scene_.materials[scene_.materialOf(hit.primitive)];
        const bool transmits = material.transmission > 0.0f;
        // SPD rules 2 and 10: primitives are one-sided, their normal the outside's (a
        // triangle's winding, away from a sphere's centre), transmitting ones included; opaque
        // ones of a two-sided scene (the teapot) face the incoming ray.
        const bool facesRay = surface.outside || (rules_.twoSided && !transmits);
        const Vec3 n = facesRay ? surface.shadingNormal : -surface.shadingNormal;
        const Vec3 view = -glm::normalize(ray.dir);
        if (eye) {
            eye->depth = hit.t * glm::length(ray.dir);
            eye->primitive = hit.primitive;
            eye->normal = n;
        }

        // The shadow ray starts on the side its normal faces, except from the inside of a
        // transmitting polygon: there it starts inside, as the ray came, and the polygon it
        // would leave through occludes it (a closed glass solid lets no shadow ray out of its
        // own faces). Spheres and cones keep the outside's start (their inside is lit through
        // the glass, as Havran's counts for mount's glass spheres show).
        const bool insideGlassPolygon = transmits && !surface.outside && hit.primitive < scene_.triangleCount();
        const Vec3 shadowOrigin = facesRay || insideGlassPolygon ? surface.originAbove() : surface.originBelow();
        Vec3 color = directLight(surface.position, n, view, material, shadowOrigin, ts);

        // SPD rules 7-9: reflection from reflective surfaces and from transmitting ones ("a ray
        // hitting a transmitting object spawns a reflection ray as well", whatever its Ks),
        // refraction through transmitting ones (total internal reflection: the reflection ray
        // only), up to the tree depth. The rays leave on the incoming side (reflection) or
        // through (refraction).
        const bool reflects = material.mirror > 0.0f || transmits;
        if (!reflects) return color;
        if (depth >= rules_.maxDepth) {
            counts.raysCutByDepth += reflects + transmits;
            return color;
        }
        const Vec3 d = glm::normalize(ray.dir);
        const Vec3& facing = surface.shadingNormal;  // toward the incoming ray
        float reflectance = material.mirror;
        if (transmits) {
            // Snell's law; entering from outside goes from index 1 to the material's.
            const float eta = surface.outside ? 1.0f / material.ior : material.ior;
            const float cosIn = -glm::dot(facing, d);
            const float k = 1.0f - eta * eta * (1.0f - cosIn * cosIn);
            if (k < 0.0f) {
                ++counts.totalInternalReflections;
                reflectance += material.transmission;  // what would have passed reflects
            } else {
                ++counts.refractionRays;
                const Vec3 refracted = eta * d + (eta * cosIn - std::sqrt(k)) * facing;
                color += material.transmission * trace({surface.originBelow(), refracted}, depth + 1, ts, nullptr);
            }
        }
        ++counts.reflectionRays;
        color += reflectance * trace({surface.originAbove(), glm::reflect(d, facing)}, depth + 1, ts, nullptr);
        return color;
    }

    const Scene& scene_;
    const Accelerator& accel_;
    const SpdRules& rules_;
    Vec3 background_;
    float lightIntensity_ = 0.0f;
};

}  // namespace

SpdResult traceSpd(const Scene& scene, const Accelerator& accel, const SpdRules& rules, Framebuffer& fb,
                   const SpdRowDone& onRow) {
    if (!scene.camera) throw inputError(scene.source, 0, "the SPD rules need the scene's own viewpoint ('v')");
    CameraSpec spec = *scene.camera;
    if (fb.width != spec.width || fb.height != spec.height)
        throw std::invalid_argument("traceSpd: the framebuffer must have the camera's resolution");
    // NFF's angle spans the outermost rays, which are at the pixels' outer corners: the
    // camera's field of view from edge to edge, a corner ray at every integer position.
    const Camera camera(spec);
    const int cornersX = spec.width + 1, cornersY = spec.height + 1;
    const SpdTracer tracer(scene, accel, rules, scene.background.value_or(Vec3(0.0f)));

    std::vector<Sample> corners(size_t(cornersX) * size_t(cornersY));
    tbb::enumerable_thread_specific<SpdThreadState> states;
    const int threads = rules.threads > 0 ? rules.threads : tbb::info::default_concurrency();
    const auto start = std::chrono::steady_clock::now();
    tbb::task_arena arena(threads);
    arena.execute([&] {
        tbb::parallel_for(0, cornersY, [&](int y) {
            SpdThreadState& ts = states.local();
            const uint64_t before = ts.result.closest.queries + ts.result.shadow.queries;
            ts.rays.resize(size_t(cornersX));
            ts.hits.resize(size_t(cornersX));
            ts.costs.resize(size_t(cornersX));
            for (int x = 0; x < cornersX; ++x) ts.rays[size_t(x)] = camera.generateRay(float(x), float(y));
            accel.findNearestBatch(ts.rays, ts.hits, ts.result.closest, ts.costs, RayCoherence::Coherent);
            for (int x = 0; x < cornersX; ++x)
                corners[size_t(y) * size_t(cornersX) + size_t(x)] =
                    tracer.eyeRay(ts.rays[size_t(x)], ts.hits[size_t(x)], ts.costs[size_t(x)], ts);
            if (onRow) onRow(ts.result.closest.queries + ts.result.shadow.queries - before);
        });
    });
    SpdResult result;
    result.traceMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    result.threads = threads;
    for (const SpdThreadState& ts : states) {
        result.counts += ts.result.counts;
        result.closest += ts.result.closest;
        result.shadow += ts.result.shadow;
    }

    // Each pixel: the average of its four corners; the first-hit AOVs of its top-left one.
    for (int y = 0; y < spec.height; ++y)
        for (int x = 0; x < spec.width; ++x) {
            const Sample* c[4] = {&corners[size_t(y) * cornersX + x], &corners[size_t(y) * cornersX + x + 1],
                                  &corners[size_t(y + 1) * cornersX + x], &corners[size_t(y + 1) * cornersX + x + 1]};
            const size_t pixel = fb.index(x, y);
            fb.color[pixel] = 0.25f * (c[0]->color + c[1]->color + c[2]->color + c[3]->color);
            fb.traversalSteps[pixel] = 0.25f * (c[0]->steps + c[1]->steps + c[2]->steps + c[3]->steps);
            fb.intersectionTests[pixel] = 0.25f * (c[0]->tests + c[1]->tests + c[2]->tests + c[3]->tests);
            fb.depth[pixel] = c[0]->depth;
            fb.primitive[pixel] = c[0]->primitive;
            fb.normal[pixel] = c[0]->normal;
        }
    return result;
}

}  // namespace bvhlab
