#include "accel/verify/conformance_checks.h"

#include <bvhlab/triangle.h>
#include "accel/verify/generated_scenes.h"
#include "accel/verify/oracle.h"
#include "accel/verify/verify_rng.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <tuple>

namespace bvhlab::verify {
namespace {

// Mixed primitives: triangles, spheres, cones against a double brute force.

struct MixedReference {
    double t = std::numeric_limits<double>::infinity();
    uint32_t primitive = kInvalidPrimitive;
    bool found() const { return primitive != kInvalidPrimitive; }
};

MixedReference nearestInDouble(const PrimitiveSet& prims, const Ray& ray) {
    MixedReference best;
    if (!ray.isValid()) return best;
    const ShearedRayT<double> sheared(ray);
    const auto consider = [&](double t, uint32_t prim) {
        if (t < best.t) best = {t, prim};
    };
    for (uint32_t prim : prims.validTriangles()) {
        TriangleHitT<double> h;
        if (intersectTriangle<double>(sheared, prims.triangles[prim], ray.tmin, ray.tmax, h)) consider(h.t, prim);
    }
    for (uint32_t prim : prims.validQuadrics()) {
        QuadricHitT<double> h;
        if (intersectQuadric<double>(ray, prims.quadric(prim), ray.tmin, ray.tmax, h)) consider(h.t, prim);
    }
    return best;
}

bool sameAnswer(const MixedReference& a, const MixedReference& b) {
    if (a.found() != b.found()) return false;
    return !a.found() || std::abs(a.t - b.t) <= 1e-4 * std::max(1.0, std::abs(a.t));
}

// A ray whose reference answer stays the same when its origin moves by 1e-5 along each axis: a
// ray grazing a sphere or cone, or passing within rounding of an edge, is right either way.
bool wellConditioned(const PrimitiveSet& prims, const Ray& ray, const MixedReference& answer) {
    for (int axis = 0; axis < 3; ++axis)
        for (const float step : {-1e-5f, 1e-5f}) {
            Ray moved = ray;
            moved.org[axis] += step;
            if (!sameAnswer(nearestInDouble(prims, moved), answer)) return false;
        }
    return true;
}

std::vector<Ray> mixedRays(const Scene& scene, uint32_t seed, double scale) {
    VerifyRng rng(seed);
    std::vector<Ray> rays;
    const auto outside = [&] { return Vec3(30.0 * rng.unitVector()); };
    const auto n = [&](int count) { return int(std::max(1.0, std::round(count * scale))); };
    for (int i = 0; i < n(400); ++i) {  // from outside at random points of the scene
        const Vec3 org = outside();
        rays.push_back({org, rng.pointWithin(10.0) - org});
    }
    for (int i = 0; i < n(400); ++i) {  // at spheres, some passing just beside them
        const Sphere& s = scene.spheres[size_t(i) % 300];
        const Vec3 org = outside();
        rays.push_back({org, s.centre + 1.2f * std::abs(s.radius) * rng.pointWithin(1.0) - org});
    }
    for (int i = 0; i < n(400); ++i) {  // at cones, around their axis
        const Cone& c = scene.cones[size_t(i) % 300];
        const Vec3 org = outside();
        const Vec3 onAxis = c.base + float(rng.uniform()) * (c.apex - c.base);
        rays.push_back({org, onAxis + 1.2f * std::abs(c.baseRadius) * rng.pointWithin(1.0) - org});
    }
    for (int i = 0; i < n(300); ++i) {  // from inside spheres
        const Sphere& s = scene.spheres[size_t(i) % 300];
        rays.push_back({s.centre + 0.5f * std::abs(s.radius) * rng.pointWithin(1.0), Vec3(rng.unitVector())});
    }
    for (int i = 0; i < n(200); ++i)  // short intervals, inside and behind the origin
        rays.push_back(
            {outside(), Vec3(rng.unitVector()), -20.0f * float(rng.uniform()), 40.0f * float(rng.uniform())});
    return rays;
}

std::string describeReference(const MixedReference& r) {
    return r.found() ? fmt::format("t={:.17g} prim={}", r.t, r.primitive) : "miss";
}

// Batch: findNearestBatch / isOccludedBatch against the single-ray calls.

bool bitEqual(const Hit& a, const Hit& b) { return std::memcmp(&a, &b, sizeof(Hit)) == 0; }

std::string describeCounters(const QueryCounters& c) {
    std::string text = fmt::format("queries {}", c.queries);
    for (const QueryCounter& counter : kQueryCounters) text += fmt::format(", {} {}", counter.key, c.*counter.count);
    return text;
}

}  // namespace

CheckResult mixedPrimitives(const Subject& subject, const CheckOptions& options) {
    CheckResult result = newResult("mixed-primitives");
    const Scene scene = makeMixedScene(7);
    const PrimitiveSet prims = scene.primitives();
    auto accel = subject.make();
    accel->build(prims);
    const BuildStats stats = statisticsOf(*accel);
    result.scenes = 1;
    if (stats.primitives == prims.validTriangles().size() && stats.primitives < prims.valid.size()) {
        result.skipped = true;
        result.note = "builds over triangles only: no spheres or cones";
        return result;
    }
    if (stats.primitives != prims.valid.size()) {
        ++result.failures;
        addExample(
            result, options, scene.name,
            fmt::format("built over {} primitives, the scene has {} valid ones", stats.primitives, prims.valid.size()));
    }
    const std::vector<Ray> rays = mixedRays(scene, 11, options.rayScale);
    for (size_t i = 0; i < rays.size(); ++i) {
        if (i % 64 == 0) reportProgress(options, i, rays.size());
        const Ray& ray = rays[i];
        const MixedReference reference = nearestInDouble(prims, ray);
        if (!wellConditioned(prims, ray, reference)) continue;
        ++result.cases;
        QueryCounters counters;
        Hit hit;
        const bool found = accel->findNearest(ray, hit, counters);
        const bool occluded = accel->isOccluded(ray, counters);
        std::string problem;
        if (found != reference.found() ||
            (found && !(std::abs(hit.t - reference.t) <= 1e-4 * std::max(1.0, reference.t))))
            problem = "closest hit";
        else if (occluded != reference.found())
            problem = fmt::format("isOccluded = {}", occluded);
        else if (counters.queries != 2)
            problem = fmt::format("two queries counted as {}", counters.queries);
        else if (found && hit.primitive != reference.primitive) {
            // A tie may name another primitive at the same t: it must be hit there.
            Ray at = ray;
            at.tmin = hit.t - 1e-3f * std::max(1.0f, hit.t), at.tmax = hit.t + 1e-3f * std::max(1.0f, hit.t);
            PrimitiveSet only = prims;
            const uint32_t one[] = {hit.primitive};
            only.valid = one;
            if (!nearestInDouble(only, at).found())
                problem = fmt::format("primitive {} is not hit there", hit.primitive);
        }
        if (problem.empty()) continue;
        ++result.failures;
        addExample(result, options, scene.name,
                   fmt::format("ray #{} {}: {}: structure {}; reference {}", i, describe(ray), problem,
                               found ? describe(hit) : "miss", describeReference(reference)));
    }
    return result;
}

namespace {

// The batch calls against the single-ray calls of the subject built over `scene`, on `rays`.
void batchOn(const Subject& subject, const CheckOptions& options, const Scene& scene, std::span<const Ray> rays,
             CheckResult& result) {
    const auto accel = buildOn(subject, scene, result, options);
    ++result.scenes;
    QueryCounters single, singleOcc;
    std::vector<Hit> expected(rays.size());
    std::vector<uint8_t> expectedOcc(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
        accel->findNearest(rays[i], expected[i], single);
        expectedOcc[i] = accel->isOccluded(rays[i], singleOcc);
    }
    const bool exact = batchIsBitExact(subject.name);
    const auto same = batchTracesPackets(subject.name) ? sameQueries : sameCounters;
    // Under either hint: a structure may take another path for each, and answers may not differ.
    for (const RayCoherence coherence : {RayCoherence::Incoherent, RayCoherence::Coherent}) {
        const char* hint = coherence == RayCoherence::Coherent ? "coherent" : "incoherent";
        QueryCounters batched, batchedOcc;
        std::vector<Hit> hits(rays.size(), Hit{1.0f, 5, 0.5f, 0.5f});  // overwritten, misses included
        std::vector<uint8_t> occluded(rays.size(), 2);
        std::vector<RayCost> costs(rays.size()), occCosts(rays.size());
        // In uneven pieces: a batch of any length, one ray or none included.
        for (size_t begin = 0, step = 0; begin < rays.size(); ++step) {
            const size_t n = std::min(rays.size() - begin, step % 4 == 0 ? size_t(1) : step % 4 == 1 ? 0 : 333 * step);
            const auto part = std::span(rays).subspan(begin, n);
            accel->findNearestBatch(part, std::span(hits).subspan(begin, n), batched,
                                    std::span(costs).subspan(begin, n), coherence);
            accel->isOccludedBatch(part, std::span(occluded).subspan(begin, n), batchedOcc,
                                   std::span(occCosts).subspan(begin, n), coherence);
            begin += n;
        }
        for (size_t i = 0; i < rays.size(); ++i) {
            ++result.cases;
            std::string problem;
            if (!(exact ? bitEqual(hits[i], expected[i]) : hitsAgree(hits[i], expected[i])))
                problem = fmt::format("findNearestBatch {}; findNearest {}{}", describe(hits[i]), describe(expected[i]),
                                      exact ? " (must be bit for bit)" : "");
            else if (occluded[i] != expectedOcc[i])
                problem = fmt::format("isOccludedBatch {}; isOccluded {}", int(occluded[i]), int(expectedOcc[i]));
            if (problem.empty()) continue;
            ++result.failures;
            addExample(result, options, scene.name,
                       fmt::format("{} ray #{} {}: {}", hint, i, describe(rays[i]), problem));
        }
        const auto counterProblem = [&](const std::string& what) {
            ++result.failures;
            addExample(result, options, scene.name, what);
        };
        if (!same(batched, single))
            counterProblem(fmt::format("{} findNearestBatch counted {}; findNearest {}", hint,
                                       describeCounters(batched), describeCounters(single)));
        if (!same(batchedOcc, singleOcc))
            counterProblem(fmt::format("{} isOccludedBatch counted {}; isOccluded {}", hint,
                                       describeCounters(batchedOcc), describeCounters(singleOcc)));
        for (const auto& [list, total, what] : {std::tuple{&costs, &batched, "findNearestBatch"},
                                                std::tuple{&occCosts, &batchedOcc, "isOccludedBatch"}}) {
            uint64_t tests = 0, steps = 0;
            for (const RayCost& c : *list) tests += c.intersectionTests, steps += c.traversalSteps;
            if (tests != total->intersectionTests || steps != total->traversalSteps)
                counterProblem(fmt::format("{} {}: per-ray costs add up to N_IT {}, N_TR {}; its counters {}", hint,
                                           what, tests, steps, describeCounters(*total)));
        }
    }
}

}  // namespace

CheckResult batch(const Subject& subject, const CheckOptions& options) {
    CheckResult result = newResult("batch");
    std::vector<Ray> rays = makeBatchRays();
    rays.resize(std::min(rays.size(), scaled(rays.size(), options)));
    batchOn(subject, options, makeBatchScene(), rays, result);
    // The user's scenes with the agreement check's rays of every kind.
    for (const NamedSceneFactory& factory : userScenes(options)) {
        const SceneCase& c = sceneCase(factory, {}, options.rayScale, false);
        std::vector<Ray> all;
        for (const auto& [kind, kindRays] : c.rays) all.insert(all.end(), kindRays.begin(), kindRays.end());
        batchOn(subject, options, c.scene, all, result);
    }
    return result;
}

}  // namespace bvhlab::verify
