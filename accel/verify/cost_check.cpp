#include "accel/verify/conformance_checks.h"

#include "accel/registry.h"
#include "accel/verify/generated_scenes.h"
#include "accel/verify/ray_generators.h"
#include "accel/verify/verify_keys.h"

#include <fmt/format.h>

#include <algorithm>
#include <span>

namespace bvhlab::verify {
namespace {

// N_IT and N_TR per closest-hit query. Their sum is the work the cost check compares: the SAH's
// cost of a ray with bvhlab's default constants (BVH::cIntersect = BVH::cTraversal = 1), so
// that the wide layouts, which test more triangles in fewer nodes, compare fairly.
struct CostPerRay {
    double intersections = 0.0, steps = 0.0;
    double work() const { return intersections + steps; }
    std::string text() const { return fmt::format("N_IT {:.1f} + N_TR {:.1f} = {:.1f}", intersections, steps, work()); }
};

CostPerRay closestHitCost(const Accelerator& accel, std::span<const Ray> rays) {
    QueryCounters counters;
    for (const Ray& ray : rays) {
        Hit hit;
        accel.findNearest(ray, hit, counters);
    }
    const double n = double(std::max<size_t>(1, rays.size()));
    return {double(counters.intersectionTests) / n, double(counters.traversalSteps) / n};
}

}  // namespace

CheckResult cost(const Subject& subject, const CheckOptions& options) {
    CheckResult result = newResult("cost");
    const Scene scene = makeCostScene();
    const auto accel = buildOn(subject, scene, result, options);
    result.scenes = 1;
    if (!accel->hasCounters()) {
        result.skipped = true;
        result.note = "no counters: N_IT and N_TR are not counted";
        return result;
    }
    std::vector<Ray> rays = generateRays(RayKind::Outside, scene.primitives(), scene.bounds, scaled(2000, options), 1);
    const std::vector<Ray> inside =
        generateRays(RayKind::Inside, scene.primitives(), scene.bounds, scaled(1000, options), 2);
    rays.insert(rays.end(), inside.begin(), inside.end());
    const auto reference = createAccelerator("sahbvh", Env(verifyKeys()));
    reference->build(scene.primitives());
    const CostPerRay sah = closestHitCost(*reference, rays);
    reportProgress(options, 1, 2);
    const CostPerRay measured = closestHitCost(*accel, rays);
    reportProgress(options, 2, 2);
    result.cases = rays.size();
    const double ratio = measured.work() / sah.work();
    result.note = fmt::format("per ray {}: {:.1f}x sahbvh's {}", measured.text(), ratio, sah.text());
    if (ratio > kCostFactor) {
        result.warning = true;
        result.note += fmt::format("; past {:g}x: right answers at an absurd cost", kCostFactor);
    }
    return result;
}

}  // namespace bvhlab::verify
