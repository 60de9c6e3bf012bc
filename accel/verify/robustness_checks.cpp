#include "accel/verify/conformance_checks.h"

#include "accel/verify/closed_meshes.h"
#include "accel/verify/generated_scenes.h"
#include "accel/verify/moved_scene.h"
#include "accel/verify/ray_generators.h"
#include "accel/verify/stress_checks.h"
#include "accel/verify/watertight_probe.h"

#include <fmt/format.h>

#include <map>
#include <mutex>
#include <tuple>

namespace bvhlab::verify {
namespace {

// A bound against a build that hangs or goes quadratic, not a timing. The slowest edge case is
// sbvh on collinear centres: about 1 s in Release, 21 s under AddressSanitizer.
#ifdef __SANITIZE_ADDRESS__
constexpr double kEdgeBuildSeconds = 120.0;
#else
constexpr double kEdgeBuildSeconds = 20.0;
#endif

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
    for (const NamedSceneFactory& factory : edgeBuildScenes(n, 3)) {
        EdgeCase c{factory.make(), {}, {}};
        c.rays = raysTowardTriangles(c.scene, 128, 9);
        // And some rays that miss the tiny ones but cross the huge triangle or the line.
        const std::vector<Ray> more = generateRays(RayKind::Outside, c.scene.primitives(), c.scene.bounds, 64, 10);
        c.rays.insert(c.rays.end(), more.begin(), more.end());
        c.reference = naiveAnswers(c.scene, c.rays);
        cases.push_back(std::move(c));
    }
    return cases;
}

}  // namespace

CheckResult buildsAtTheEdge(const Subject& subject, const CheckOptions& options) {
    CheckResult result = newResult("builds-at-the-edge", "builds");
    const std::vector<EdgeCase>& cases = edgeCases(options.edgePrimitives);
    const double maxSeconds = options.edgeMaxSeconds > 0 ? options.edgeMaxSeconds : kEdgeBuildSeconds;
    // Every structure is held to bounded time and memory; an external one's answers (Embree's
    // float test on a huge triangle among tiny ones) are reported, as `bvhlab stress` does.
    size_t reported = 0;
    for (const EdgeCase& c : cases) {
        auto accel = subject.make();
        const EdgeBuildCheck check =
            checkEdgeBuild(*accel, c.scene, c.rays, c.reference, maxSeconds, options.threads, options.maxExamples);
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
        reportProgress(options, result.scenes, cases.size());
    }
    if (reported) result.note = fmt::format("{} answers unlike naive's reported, not failed", reported);
    return result;
}

const ProbedMeshes& probedMeshes(const CheckOptions& options, size_t rays, bool moved) {
    static std::mutex mutex;
    static std::map<std::tuple<double, size_t, bool>, ProbedMeshes> cache;
    const std::lock_guard lock(mutex);
    ProbedMeshes& slot = cache[{options.rayScale, rays, moved}];
    if (slot.empty())
        for (Scene scene : {makeIcosphereMesh(3), makeSubdividedCubeMesh(8), makeTorusMesh(48, 24)}) {
            if (moved) scene = movedScene(scene);
            ProbeOptions probeOptions;
            probeOptions.rays = scaled(rays, options);
            probeOptions.seed = scene.triangleCount();
            ProbeSet probes = makeWatertightProbes(MeshTopology::of(scene), probeOptions);
            slot.emplace_back(std::move(scene), std::move(probes));
        }
    return slot;
}

void tallyLeaks(const Subject& subject, const CheckOptions& options, const Scene& scene, const LeakStats& stats,
                CheckResult& result, size_t& reported) {
    result.cases += stats.rays;
    const size_t leaks = stats.leaks + stats.occlusionLeaks;
    if (isExternal(subject.name)) {
        reported += leaks;
        return;
    }
    result.failures += leaks + stats.batchLeaks + stats.batchOcclusionLeaks;
    for (const std::string& e : stats.examples)
        addExample(result, options, scene.name, e + " (tmin 0); reference: a hit in [0, tmax]");
}

CheckResult watertight(const Subject& subject, const CheckOptions& options) {
    CheckResult result = newResult("watertight", "probes");
    const ProbedMeshes& meshes = probedMeshes(options, 10000, false);
    size_t reported = 0;
    for (const auto& [scene, probes] : meshes) {
        const auto accel = buildOn(subject, scene, result, options);
        ++result.scenes;
        tallyLeaks(subject, options, scene, countLeaks(*accel, probes.probes, options.threads, options.maxExamples),
                   result, reported);
        reportProgress(options, result.scenes, meshes.size());
    }
    if (reported)
        result.note =
            fmt::format("{} leaks reported, not failed: {} promises no watertightness", reported, subject.name);
    return result;
}

}  // namespace bvhlab::verify
