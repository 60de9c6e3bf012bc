#include "apps/runtime/ray_sets.h"

#include "accel/registry.h"
#include "framework/core/error.h"
#include "framework/render/renderer.h"
#include "framework/scene/surface_point.h"

#include <fmt/core.h>
#include <tbb/parallel_for.h>
#include <glm/gtc/constants.hpp>

#include <random>

namespace bvhlab {
namespace {

// Cosine-distributed direction around the unit normal n (Malley's method).
Vec3 cosineDirection(const Vec3& n, float u1, float u2) {
    const float r = std::sqrt(u1), phi = glm::two_pi<float>() * u2;
    const Vec3 t = std::abs(n.x) > 0.9f ? glm::normalize(glm::cross(n, Vec3(0, 1, 0)))
                                        : glm::normalize(glm::cross(n, Vec3(1, 0, 0)));
    const Vec3 b = glm::cross(n, t);
    return r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0f, 1.0f - u1)) * n;
}

}  // namespace

RaySets makeRaySets(const Scene& scene, const Camera& camera, const std::vector<PointLight>& lights,
                    const Accelerator& reference, float aoRadiusFraction, uint32_t seed) {
    RaySets sets;
    for (int y = 0; y < camera.height(); ++y)
        for (int x = 0; x < camera.width(); ++x) sets.primary.push_back(camera.generateRay(x + 0.5f, y + 0.5f));

    std::vector<Hit> hits(sets.primary.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, hits.size(), 4096), [&](const auto& range) {
        QueryCounters unused;
        for (size_t i = range.begin(); i < range.end(); ++i) reference.findNearest(sets.primary[i], hits[i], unused);
    });

    const float aoRadius = aoRadiusFraction * glm::length(scene.bounds.diagonal());
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (size_t i = 0; i < hits.size(); ++i) {
        if (!hits[i].found()) continue;
        const SurfacePoint surface = surfaceAt(scene, sets.primary[i], hits[i]);
        const Vec3& p = surface.position;
        const Vec3& n = surface.geometricNormal;
        const Vec3 origin = surface.originAbove();
        for (const PointLight& light : lights)
            if (glm::dot(n, light.position - p) > 0.0f)
                sets.shadow.push_back({origin, light.position - origin, 0.0f, 1.0f - 1e-5f});
        sets.incoherent.push_back({origin, cosineDirection(n, uniform(rng), uniform(rng)), 0.0f, aoRadius});
    }
    return sets;
}

RaySets sceneRaySets(const Scene& scene, const Env& env, const Accelerator& reference) {
    const Camera camera(resolveCamera(scene, env));
    const RenderSettings render = RenderSettings::fromEnv(env, scene, camera.spec());
    return makeRaySets(scene, camera, render.lights, reference);
}

std::vector<Ray> benchRays(const Scene& scene, const Env& env, const std::string& kind) {
    if (kind != "primary" && kind != "shadow" && kind != "incoherent")
        throw InputError(fmt::format("unknown kind of rays '{}' (primary, shadow or incoherent)", kind));
    // Embree finds the surfaces the shadow and incoherent rays leave from, as in the bench.
    const std::unique_ptr<Accelerator> reference = createAccelerator("embree", env);
    reference->build(scene.primitives());
    RaySets sets = sceneRaySets(scene, env, *reference);
    return std::move(kind == "primary" ? sets.primary : kind == "shadow" ? sets.shadow : sets.incoherent);
}

}  // namespace bvhlab
