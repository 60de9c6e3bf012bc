#include "accel/verify/conformance_checks.h"

#include "accel/verify/comparison.h"
#include "accel/verify/generated_scenes.h"
#include "accel/verify/ray_generators.h"
#include "accel/verify/verify_rng.h"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <mutex>

namespace bvhlab::verify {

const SceneCase& sceneCase(const NamedSceneFactory& factory, const std::vector<Ray>& extraRays, double rayScale,
                           bool judged) {
    static std::mutex mutex;
    static std::map<std::pair<std::string, double>, std::unique_ptr<SceneCase>> cache;
    const std::lock_guard lock(mutex);
    auto& slot = cache[{factory.name, rayScale}];
    if (slot) {
        if (judged && slot->reference.empty())
            for (const auto& [kind, rays] : slot->rays)
                slot->reference.push_back(computeOracleReference(*slot->oracle, rays));
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
        for (const auto& [kind, rays] : slot->rays)
            slot->reference.push_back(computeOracleReference(*slot->oracle, rays));
    return *slot;
}

namespace {

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
            const std::string label =
                fmt::format("{}/{}", factory.name, k < std::size(kAllRayKinds) ? rayKindName(kind) : "aimed");
            const ComparisonReport r = compareWithReference(*accel, nearest ? c.reference[k] : unjudged, *c.oracle,
                                                            rays, options.maxExamples, occlusion);
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
            reportProgress(options, ++done, total);
        }
    }
    if (reported)
        result.note =
            fmt::format("{} known deviations reported (within {:g} % of each ray set)", reported, 100 * kExternalBound);
    return result;
}

// Rays aimed at the finite vertices of the degenerate triangles (and at their midpoints), from
// random directions and along z: whatever they hit must be a valid primitive.
std::vector<Ray> raysAtDegenerateTriangles(const Scene& scene) {
    VerifyRng rng(99);
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

}  // namespace

std::vector<NamedSceneFactory> agreementScenes() {
    std::vector<NamedSceneFactory> scenes;
    for (const NamedSceneFactory& f : generatedScenes())
        if (f.name != "degenerate_mix") scenes.push_back(f);  // the degenerate-triangles check's
    return scenes;
}

namespace {

// The agreement scenes, then the user's.
std::vector<NamedSceneFactory> agreementAndUserScenes(const CheckOptions& options) {
    std::vector<NamedSceneFactory> scenes = agreementScenes();
    for (NamedSceneFactory& f : userScenes(options)) scenes.push_back(std::move(f));
    return scenes;
}

}  // namespace

CheckResult agreement(const Subject& subject, const CheckOptions& options) {
    return compareOnScenes(subject, options, "agreement", agreementAndUserScenes(options), {}, Queries::Nearest);
}

CheckResult anyHit(const Subject& subject, const CheckOptions& options) {
    return compareOnScenes(subject, options, "any-hit", agreementAndUserScenes(options), {}, Queries::Occlusion);
}

CheckResult degenerateTriangles(const Subject& subject, const CheckOptions& options) {
    const std::vector<NamedSceneFactory> scenes = {{"degenerate_mix", [] { return makeDegenerateMixScene(2000, 12); }}};
    return compareOnScenes(subject, options, "degenerate-triangles", scenes, raysAtDegenerateTriangles, Queries::Both);
}

}  // namespace bvhlab::verify
