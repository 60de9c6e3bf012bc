#include "apps/check/conformance.h"

#include "accel/registry.h"
#include "apps/check/oracle.h"
#include "apps/runtime/program_keys.h"
#include "framework/core/error.h"
#include "framework/core/timed_build.h"
#include "framework/robustness/stress_checks.h"
#include "framework/robustness/stress_rng.h"
#include "framework/robustness/stress_scenes.h"
#include "framework/robustness/watertight_probe.h"
#include "framework/scene/procedural.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <tuple>

namespace bvhlab::check {
namespace {

// Known deviations of an external structure (Embree without ROBUST leaks at edges) are reported,
// and fail only above this fraction of a ray set.
constexpr double kExternalBound = 0.01;

// A bound against a build that hangs or goes quadratic, not a timing. The slowest edge case is
// sbvh on collinear centres: about 1 s in Release, 21 s under AddressSanitizer.
#ifdef __SANITIZE_ADDRESS__
constexpr double kEdgeBuildSeconds = 120.0;
#else
constexpr double kEdgeBuildSeconds = 20.0;
#endif

CheckResult newResult(std::string check, std::string unit = "rays") {
    CheckResult result;
    result.check = std::move(check);
    result.unit = std::move(unit);
    return result;
}

size_t scaled(size_t count, const CheckOptions& options) {
    return std::max<size_t>(1, size_t(std::llround(double(count) * options.rayScale)));
}

void progress(const CheckOptions& options, uint64_t done, uint64_t total) {
    if (options.progress) options.progress(done, total);
}

// Adds a failure's text (naming the check and the scene) while there is room.
void addExample(CheckResult& result, const CheckOptions& options, const std::string& scene, const std::string& what) {
    if (result.examples.size() < options.maxExamples)
        result.examples.push_back(fmt::format("{} on {}: {}", result.check, scene, what));
}

std::unique_ptr<Accelerator> buildOn(const Subject& subject, const Scene& scene, CheckResult& result,
                                     const CheckOptions& options, BuildStats* stats = nullptr) {
    auto accel = subject.make();
    const BuildStats s = timedBuild(*accel, scene.primitives());
    if (s.primitives != scene.validPrimitives.size()) {
        ++result.failures;
        addExample(result, options, scene.name,
                   fmt::format("built over {} primitives, the scene has {} valid ones", s.primitives,
                               scene.validPrimitives.size()));
    }
    if (stats) *stats = s;
    return accel;
}

// --- agreement and any-hit: the generated scenes, every ray kind, against the oracle ----------

// One scene with its oracle and, per ray kind, the rays and (when a check judges answers) the
// oracle's answers: computed once per process, shared by every structure and check.
struct SceneCase {
    Scene scene;
    std::unique_ptr<Oracle> oracle;
    std::vector<std::pair<RayKind, std::vector<Ray>>> rays;
    std::vector<Reference> reference;
};

const SceneCase& sceneCase(const NamedSceneFactory& factory, const std::vector<Ray>& extraRays, double rayScale,
                           bool judged) {
    static std::mutex mutex;
    static std::map<std::pair<std::string, double>, std::unique_ptr<SceneCase>> cache;
    const std::lock_guard lock(mutex);
    auto& slot = cache[{factory.name, rayScale}];
    if (slot) {
        if (judged && slot->reference.empty())
            for (const auto& [kind, rays] : slot->rays) slot->reference.push_back(computeOracleReference(*slot->oracle, rays));
        return *slot;
    }
    slot = std::make_unique<SceneCase>();
    slot->scene = factory.make();
    slot->scene.name = factory.name;
    const Scene& scene = slot->scene;
    slot->oracle = std::make_unique<Oracle>(scene.primitives());
    uint32_t seed = 2166136261u;  // FNV-1a of the name: the same rays on every platform
    for (const char ch : factory.name) seed = (seed ^ uint8_t(ch)) * 16777619u;
    for (RayKind kind : kAllRayKinds) {
        const size_t count = std::max<size_t>(1, size_t(std::llround(double(raysPerKind(scene, kind)) * rayScale)));
        slot->rays.emplace_back(kind, generateRays(kind, scene.primitives(), scene.bounds, count, ++seed));
    }
    if (!extraRays.empty()) slot->rays.emplace_back(RayKind::Outside, extraRays);
    if (judged)
        for (const auto& [kind, rays] : slot->rays) slot->reference.push_back(computeOracleReference(*slot->oracle, rays));
    return *slot;
}

enum class Queries { Nearest, Occlusion, Both };

// Compares the structure with the oracle on every ray set of `scenes`, counting the failures of
// `queries`; an external structure's are reported up to kExternalBound of a ray set.
CheckResult compareOnScenes(const Subject& subject, const CheckOptions& options, const std::string& check,
                            const std::vector<NamedSceneFactory>& scenes,
                            const std::function<std::vector<Ray>(const Scene&)>& extraRays, Queries queries) {
    CheckResult result = newResult(check);
    size_t reported = 0, done = 0;
    const size_t total = scenes.size() * std::size(kAllRayKinds);
    for (const NamedSceneFactory& factory : scenes) {
        const std::vector<Ray> extra = extraRays ? extraRays(factory.make()) : std::vector<Ray>{};
        const bool nearest = queries != Queries::Occlusion, occlusion = queries != Queries::Nearest;
        // isOccluded is checked against the structure's own closest hits: no oracle needed.
        const SceneCase& c = sceneCase(factory, extra, options.rayScale, nearest);
        static const Reference unjudged;
        const auto accel = buildOn(subject, c.scene, result, options);
        ++result.scenes;
        for (size_t k = 0; k < c.rays.size(); ++k) {
            const auto& [kind, rays] = c.rays[k];
            const std::string label = fmt::format("{}/{}", factory.name, k < std::size(kAllRayKinds) ? rayKindName(kind) : "aimed");
            const ComparisonReport r = compareWithReference(*accel, nearest ? c.reference[k] : unjudged, *c.oracle, rays,
                                                            options.maxExamples, occlusion);
            const size_t failures = (nearest ? r.nearestFailures() : 0) + (occlusion ? r.occlusionFailures() : 0);
            result.cases += r.rays;
            if (isExternal(subject.name) && double(failures) <= kExternalBound * double(r.rays)) {
                reported += failures;
            } else {
                result.failures += failures;
                if (nearest)
                    for (const std::string& e : r.examples) addExample(result, options, label, e);
                if (occlusion)
                    for (const std::string& e : r.occlusionExamples) addExample(result, options, label, e);
            }
            progress(options, ++done, total);
        }
    }
    if (reported) result.note = fmt::format("{} known deviations reported (within {:g} % of each ray set)", reported, 100 * kExternalBound);
    return result;
}

std::vector<NamedSceneFactory> agreementScenes() {
    std::vector<NamedSceneFactory> scenes;
    for (const NamedSceneFactory& f : generatedScenes())
        if (f.name != "degenerate_mix") scenes.push_back(f);  // the degenerate-triangles check's
    return scenes;
}

CheckResult agreement(const Subject& subject, const CheckOptions& options) {
    return compareOnScenes(subject, options, "agreement", agreementScenes(), {}, Queries::Nearest);
}

CheckResult anyHit(const Subject& subject, const CheckOptions& options) {
    return compareOnScenes(subject, options, "any-hit", agreementScenes(), {}, Queries::Occlusion);
}

// Rays aimed at the finite vertices of the degenerate triangles (and at their midpoints), from
// random directions and along z: whatever they hit must be a valid primitive.
std::vector<Ray> raysAtDegenerateTriangles(const Scene& scene) {
    StressRng rng(99);
    std::vector<uint8_t> valid(scene.triangleCount(), 0);
    for (uint32_t p : scene.validPrimitives) valid[p] = 1;
    std::vector<Ray> rays;
    for (size_t i = 0; i < scene.triangleCount(); ++i) {
        if (valid[i]) continue;
        const Triangle& t = scene.triangles[i];
        for (const Vec3& target : {t.v0, t.v1, t.v2, 0.5f * (t.v0 + t.v1)}) {
            if (!isFinite(target)) continue;
            for (int k = 0; k < 3; ++k) {
                const Vec3 org = target + Vec3(30.0 * rng.unitVector());
                rays.push_back(Ray(org, target - org));
            }
            rays.push_back(Ray(target - Vec3(0, 0, 40), Vec3(0, 0, 1)));
        }
    }
    return rays;
}

CheckResult degenerateTriangles(const Subject& subject, const CheckOptions& options) {
    const std::vector<NamedSceneFactory> scenes = {{"degenerate_mix", [] { return makeDegenerateMixScene(2000, 12); }}};
    return compareOnScenes(subject, options, "degenerate-triangles", scenes, raysAtDegenerateTriangles, Queries::Both);
}

// --- mixed primitives: triangles, spheres, cones against a double brute force ----------------

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

Vec3 pointWithin(StressRng& rng, double radius) { return Vec3(rng.unitVector() * (radius * rng.uniform())); }

std::vector<Ray> mixedRays(const Scene& scene, uint32_t seed, double scale) {
    StressRng rng(seed);
    std::vector<Ray> rays;
    const auto outside = [&] { return Vec3(30.0 * rng.unitVector()); };
    const auto n = [&](int count) { return int(std::max(1.0, std::round(count * scale))); };
    for (int i = 0; i < n(400); ++i) {  // from outside at random points of the scene
        const Vec3 org = outside();
        rays.push_back({org, pointWithin(rng, 10.0) - org});
    }
    for (int i = 0; i < n(400); ++i) {  // at spheres, some passing just beside them
        const Sphere& s = scene.spheres[size_t(i) % 300];
        const Vec3 org = outside();
        rays.push_back({org, s.centre + 1.2f * std::abs(s.radius) * pointWithin(rng, 1.0) - org});
    }
    for (int i = 0; i < n(400); ++i) {  // at cones, around their axis
        const Cone& c = scene.cones[size_t(i) % 300];
        const Vec3 org = outside();
        const Vec3 onAxis = c.base + float(rng.uniform()) * (c.apex - c.base);
        rays.push_back({org, onAxis + 1.2f * std::abs(c.baseRadius) * pointWithin(rng, 1.0) - org});
    }
    for (int i = 0; i < n(300); ++i) {  // from inside spheres
        const Sphere& s = scene.spheres[size_t(i) % 300];
        rays.push_back({s.centre + 0.5f * std::abs(s.radius) * pointWithin(rng, 1.0), Vec3(rng.unitVector())});
    }
    for (int i = 0; i < n(200); ++i)  // short intervals, inside and behind the origin
        rays.push_back({outside(), Vec3(rng.unitVector()), -20.0f * float(rng.uniform()), 40.0f * float(rng.uniform())});
    return rays;
}

std::string describeReference(const MixedReference& r) { return r.found() ? fmt::format("t={:.17g} prim={}", r.t, r.primitive) : "miss"; }

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
        addExample(result, options, scene.name,
                   fmt::format("built over {} primitives, the scene has {} valid ones", stats.primitives, prims.valid.size()));
    }
    const std::vector<Ray> rays = mixedRays(scene, 11, options.rayScale);
    for (size_t i = 0; i < rays.size(); ++i) {
        if (i % 64 == 0) progress(options, i, rays.size());
        const Ray& ray = rays[i];
        const MixedReference reference = nearestInDouble(prims, ray);
        if (!wellConditioned(prims, ray, reference)) continue;
        ++result.cases;
        QueryCounters counters;
        Hit hit;
        const bool found = accel->findNearest(ray, hit, counters);
        const bool occluded = accel->isOccluded(ray, counters);
        std::string problem;
        if (found != reference.found() || (found && !(std::abs(hit.t - reference.t) <= 1e-4 * std::max(1.0, reference.t))))
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
            if (!nearestInDouble(only, at).found()) problem = fmt::format("primitive {} is not hit there", hit.primitive);
        }
        if (problem.empty()) continue;
        ++result.failures;
        addExample(result, options, scene.name,
                   fmt::format("ray #{} {}: {}: structure {}; reference {}", i, describe(ray), problem,
                               found ? describe(hit) : "miss", describeReference(reference)));
    }
    return result;
}

// --- batch: findNearestBatch / isOccludedBatch against the single-ray calls -------------------

bool bitEqual(const Hit& a, const Hit& b) { return std::memcmp(&a, &b, sizeof(Hit)) == 0; }

std::string describeCounters(const QueryCounters& c) {
    return fmt::format("queries {}, N_IT {}, N_TR {}, spheres {}, cones {}", c.queries, c.intersectionTests,
                       c.traversalSteps, c.sphereTests, c.coneTests);
}

CheckResult batch(const Subject& subject, const CheckOptions& options) {
    CheckResult result = newResult("batch");
    const Scene scene = makeBatchScene();
    const auto accel = buildOn(subject, scene, result, options);
    result.scenes = 1;
    std::vector<Ray> rays = makeBatchRays();
    rays.resize(std::min(rays.size(), scaled(rays.size(), options)));

    QueryCounters single, batched, singleOcc, batchedOcc;
    std::vector<Hit> expected(rays.size());
    std::vector<uint8_t> expectedOcc(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
        accel->findNearest(rays[i], expected[i], single);
        expectedOcc[i] = accel->isOccluded(rays[i], singleOcc);
    }
    std::vector<Hit> hits(rays.size(), Hit{1.0f, 5, 0.5f, 0.5f});  // overwritten, misses included
    std::vector<uint8_t> occluded(rays.size(), 2);
    std::vector<RayCost> costs(rays.size()), occCosts(rays.size());
    // In uneven pieces: a batch of any length, one ray or none included.
    for (size_t begin = 0, step = 0; begin < rays.size(); ++step) {
        const size_t n = std::min(rays.size() - begin, step % 4 == 0 ? size_t(1) : step % 4 == 1 ? 0 : 333 * step);
        const auto part = std::span(rays).subspan(begin, n);
        accel->findNearestBatch(part, std::span(hits).subspan(begin, n), batched, std::span(costs).subspan(begin, n));
        accel->isOccludedBatch(part, std::span(occluded).subspan(begin, n), batchedOcc, std::span(occCosts).subspan(begin, n));
        begin += n;
    }
    const bool exact = batchIsBitExact(subject.name);
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
        addExample(result, options, scene.name, fmt::format("ray #{} {}: {}", i, describe(rays[i]), problem));
    }
    const auto counterProblem = [&](const std::string& what) {
        ++result.failures;
        addExample(result, options, scene.name, what);
    };
    const auto same = batchTracesPackets(subject.name) ? sameQueries : sameCounters;
    if (!same(batched, single))
        counterProblem(fmt::format("findNearestBatch counted {}; findNearest {}", describeCounters(batched), describeCounters(single)));
    if (!same(batchedOcc, singleOcc))
        counterProblem(fmt::format("isOccludedBatch counted {}; isOccluded {}", describeCounters(batchedOcc), describeCounters(singleOcc)));
    for (const auto& [list, total, what] : {std::tuple{&costs, &batched, "findNearestBatch"}, std::tuple{&occCosts, &batchedOcc, "isOccludedBatch"}}) {
        uint64_t tests = 0, steps = 0;
        for (const RayCost& c : *list) tests += c.intersectionTests, steps += c.traversalSteps;
        if (tests != total->intersectionTests || steps != total->traversalSteps)
            counterProblem(fmt::format("{}: per-ray costs add up to N_IT {}, N_TR {}; its counters {}", what, tests, steps,
                                       describeCounters(*total)));
    }
    return result;
}

// --- watertight: probes at the edges and vertices of closed meshes ----------------------------

CheckResult watertight(const Subject& subject, const CheckOptions& options) {
    CheckResult result = newResult("watertight", "probes");
    static std::mutex mutex;
    static std::map<double, std::vector<std::pair<Scene, ProbeSet>>> cache;
    std::vector<std::pair<Scene, ProbeSet>>* meshes;
    {
        const std::lock_guard lock(mutex);
        auto& slot = cache[options.rayScale];
        if (slot.empty())
            for (Scene scene : {makeIcosphereMesh(3), makeSubdividedCubeMesh(8), makeTorusMesh(48, 24)}) {
                ProbeOptions probeOptions;
                probeOptions.rays = scaled(10000, options);
                probeOptions.seed = scene.triangleCount();
                ProbeSet probes = makeWatertightProbes(MeshTopology::of(scene), probeOptions);
                slot.emplace_back(std::move(scene), std::move(probes));
            }
        meshes = &slot;
    }
    const bool promised = !isExternal(subject.name);
    size_t reported = 0;
    for (const auto& [scene, probes] : *meshes) {
        const auto accel = buildOn(subject, scene, result, options);
        ++result.scenes;
        const LeakStats s = countLeaks(*accel, probes.probes, options.threads, options.maxExamples);
        result.cases += s.rays;
        const size_t leaks = s.leaks + s.occlusionLeaks;
        if (!promised) {
            reported += leaks;
        } else {
            result.failures += leaks + s.batchLeaks + s.batchOcclusionLeaks;
            for (const std::string& e : s.examples)
                addExample(result, options, scene.name, e + " (tmin 0); reference: a hit in [0, tmax]");
        }
        progress(options, result.scenes, meshes->size());
    }
    if (reported) result.note = fmt::format("{} leaks reported, not failed: {} promises no watertightness", reported, subject.name);
    return result;
}

// --- builds at the edge: bounded time and memory on degenerate inputs --------------------------

struct EdgeCase {
    Scene scene;
    std::vector<Ray> rays;
    std::vector<Hit> reference;  // naive's
};

const std::vector<EdgeCase>& edgeCases(size_t n) {
    static std::mutex mutex;
    static std::map<size_t, std::vector<EdgeCase>> cache;
    const std::lock_guard lock(mutex);
    auto& cases = cache[n];
    if (!cases.empty()) return cases;
    const auto naive = createAccelerator("naive", Env(programKeys()));
    for (Scene scene : {makeIdenticalTrianglesScene(n), makeCollinearCentroidsScene(n, 3), makeHugeAmongTinyScene(n, 4)}) {
        EdgeCase c{std::move(scene), {}, {}};
        c.rays = raysTowardTriangles(c.scene, 128, 9);
        // And some rays that miss the tiny ones but cross the huge triangle or the line.
        const std::vector<Ray> more = generateRays(RayKind::Outside, c.scene.primitives(), c.scene.bounds, 64, 10);
        c.rays.insert(c.rays.end(), more.begin(), more.end());
        naive->build(c.scene.primitives());
        QueryCounters counters;
        c.reference.resize(c.rays.size());
        naive->findNearestBatch(c.rays, c.reference, counters, {});
        cases.push_back(std::move(c));
    }
    return cases;
}

CheckResult buildsAtTheEdge(const Subject& subject, const CheckOptions& options) {
    CheckResult result = newResult("builds-at-the-edge", "builds");
    const std::vector<EdgeCase>& cases = edgeCases(options.edgePrimitives);
    const double maxSeconds = options.edgeMaxSeconds > 0 ? options.edgeMaxSeconds : kEdgeBuildSeconds;
    // Every structure is held to bounded time and memory; an external one's answers (Embree's
    // float test on a huge triangle among tiny ones) are reported, as `bvhlab stress` does.
    size_t reported = 0;
    for (const EdgeCase& c : cases) {
        auto accel = subject.make();
        const EdgeBuildCheck check = checkEdgeBuild(*accel, c.scene, c.rays, c.reference, maxSeconds, options.threads,
                                                    options.maxExamples);
        ++result.scenes;
        ++result.cases;
        result.failures += check.problems.size();
        for (const std::string& p : check.problems) addExample(result, options, c.scene.name, p);
        if (isExternal(subject.name)) {
            reported += check.differ;
        } else {
            result.failures += check.differ;
            for (const std::string& e : check.examples) addExample(result, options, c.scene.name, e);
        }
        progress(options, result.scenes, cases.size());
    }
    if (reported) result.note = fmt::format("{} answers unlike naive's reported, not failed", reported);
    return result;
}

// --- cost: N_IT and N_TR per ray against sahbvh's ---------------------------------------------

// A structure that answers right but works this many times harder per ray than sahbvh is
// warned about, not failed (docs/accuracy.md: how far our own structures are from it).
constexpr double kCostFactor = 10.0;

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
    const std::vector<Ray> inside = generateRays(RayKind::Inside, scene.primitives(), scene.bounds, scaled(1000, options), 2);
    rays.insert(rays.end(), inside.begin(), inside.end());
    const auto reference = createAccelerator("sahbvh", Env(programKeys()));
    reference->build(scene.primitives());
    const CostPerRay sah = closestHitCost(*reference, rays);
    progress(options, 1, 2);
    const CostPerRay measured = closestHitCost(*accel, rays);
    progress(options, 2, 2);
    result.cases = rays.size();
    const double ratio = measured.work() / sah.work();
    result.note = fmt::format("per ray {}: {:.1f}x sahbvh's {}", measured.text(), ratio, sah.text());
    if (ratio > kCostFactor) {
        result.warning = true;
        result.note += fmt::format("; past {:g}x: right answers at an absurd cost", kCostFactor);
    }
    return result;
}

}  // namespace

bool isExternal(std::string_view accelerator) { return accelerator.starts_with("embree"); }

bool batchTracesPackets(std::string_view accelerator) {
    return !isExternal(accelerator) && (accelerator.ends_with('4') || accelerator.ends_with('8'));
}

bool sameCounters(const QueryCounters& a, const QueryCounters& b) {
    return a.queries == b.queries && a.intersectionTests == b.intersectionTests &&
           a.traversalSteps == b.traversalSteps && a.sphereTests == b.sphereTests && a.coneTests == b.coneTests;
}

bool sameQueries(const QueryCounters& a, const QueryCounters& b) {
    return a.queries == b.queries && a.sphereTests == b.sphereTests && a.coneTests == b.coneTests;
}


Scene makeMixedScene(uint32_t seed) {
    StressRng rng(seed);
    const auto point = [&] { return pointWithin(rng, 10.0); };
    const auto unit = [&] { return float(rng.uniform()); };
    Scene scene;
    scene.name = "mixed";
    for (int i = 0; i < 300; ++i) {
        const Vec3 c = point();
        const float size = 0.2f + 2.0f * unit();
        const auto base = uint32_t(scene.positions.size());
        for (int k = 0; k < 3; ++k) scene.positions.push_back(c + size * Vec3(rng.unitVector()));
        scene.indices.push_back({base, base + 1, base + 2});
    }
    scene.indices.push_back({0, 0, 0});  // degenerate
    for (int i = 0; i < 300; ++i) {
        const float r = 0.05f + 1.5f * unit();
        scene.spheres.push_back({point(), i % 10 == 0 ? -r : r});
    }
    scene.spheres.push_back({point(), 0.0f});  // degenerate
    for (int i = 0; i < 300; ++i) {
        const Vec3 base = point();
        const Vec3 apex = base + (0.3f + 3.0f * unit()) * Vec3(rng.unitVector());
        const float r0 = 0.05f + unit(), kind = unit();
        const float r1 = kind < 0.3f ? r0 : (kind < 0.6f ? 0.0f : r0 * unit());  // cylinder, cone, truncated
        scene.cones.push_back({base, r0, apex, r1});
    }
    scene.cones.push_back({point(), 1.0f, point(), -1.0f});  // degenerate: radii of opposite signs
    scene.finalize();
    return scene;
}

Scene makeBatchScene() {
    Scene scene;
    scene.name = "batch";
    scene.materials = {{Vec3(0.6f), 0.0f}, {Vec3(0.3f), 0.7f}};
    addQuad(scene, Vec3(-6, -2, -6), Vec3(0, 0, 12), Vec3(12, 0, 0), 1);
    addIcosphere(scene, Vec3(-2, 0, 0), 1.5f, 3, 0);
    addBox(scene, Vec3(1, -1, -1), Vec3(3, 1.5f, 1), 0);
    StressRng rng(7);
    for (int i = 0; i < 40; ++i) scene.spheres.push_back({pointWithin(rng, 5.0), 0.1f + 0.02f * float(i)});
    for (int i = 0; i < 40; ++i) {
        const Vec3 base = pointWithin(rng, 5.0);
        scene.cones.push_back({base, 0.3f, base + Vec3(rng.unitVector()), i % 2 ? 0.0f : 0.2f});
    }
    scene.finalize();
    return scene;
}

std::vector<Ray> makeBatchRays() {
    StressRng rng(11);
    std::vector<Ray> rays;
    for (int i = 0; i < 3000; ++i) {
        const Vec3 org = pointWithin(rng, 12.0);
        Ray r{org, pointWithin(rng, 4.0) - org};
        if (i % 7 == 0) r.dir = Vec3(0.0f), r.dir[i % 3] = i % 2 ? 1.0f : -1.0f;
        if (i % 5 == 0) r.tmin = -10.0f * float(rng.uniform());
        if (i % 11 == 0) r.tmax = 2.0f * float(rng.uniform());
        if (i % 13 == 0) r.tmin = 3.0f, r.tmax = 1.0f;
        if (i % 17 == 0) r.org.y = std::numeric_limits<float>::quiet_NaN();
        rays.push_back(r);
    }
    return rays;
}

const std::vector<CheckInfo>& conformanceChecks() {
    static const std::vector<CheckInfo> checks = {
        {"agreement", "closest hit against the double-precision reference on every generated scene and ray kind", agreement},
        {"any-hit", "isOccluded answers as the closest hit does, and nothing blocks a ray before it", anyHit},
        {"batch", "findNearestBatch/isOccludedBatch answer and count as the single-ray calls", batch},
        {"mixed-primitives", "triangles, spheres and cones against a double brute force (if supported)", mixedPrimitives},
        {"degenerate-triangles", "degenerate triangles mixed in are never hit; rays aimed at them", degenerateTriangles},
        {"watertight", "probes at the edges and vertices of closed meshes do not leak (if promised)", watertight},
        {"builds-at-the-edge", "bounded time, memory and depth on degenerate inputs, answers as naive's", buildsAtTheEdge},
        {"cost", fmt::format("N_IT + N_TR per ray against sahbvh's on a mid-size scene: a warning past {:g}x", kCostFactor), cost},
    };
    return checks;
}

std::vector<std::string> checkNames() {
    std::vector<std::string> names;
    for (const CheckInfo& c : conformanceChecks()) names.push_back(c.name);
    return names;
}

const CheckInfo& findCheck(const std::string& name) {
    for (const CheckInfo& c : conformanceChecks())
        if (c.name == name) return c;
    throw InputError(fmt::format("unknown check '{}' (known: {})", name, fmt::join(checkNames(), ", ")));
}

CheckResult runCheck(const std::string& name, const Subject& subject, const CheckOptions& options) {
    const CheckInfo& info = findCheck(name);
    const auto start = std::chrono::steady_clock::now();
    CheckResult result = info.run(subject, options);
    result.check = info.name;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace bvhlab::check
