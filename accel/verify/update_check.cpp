#include "accel/verify/conformance_checks.h"
#include "accel/verify/moved_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

namespace bvhlab::verify {
namespace {

// The rays of every `stride`-th on which `updated` answers otherwise than `fresh`, a build
// over the same moved primitives: a closest hit at another t (hitsAgree) or another occlusion.
// A tie may name another primitive; with a reference, a ray on which it judges either answer
// ambiguous (within rounding of an edge or an interval end, where a box of either tree may
// round the other way) may differ too. Returns their count and the first few as examples.
struct Differences {
    size_t rays = 0, count = 0;
    std::vector<std::string> examples;
};
Differences differencesFromFresh(const Accelerator& updated, const Accelerator& fresh, std::span<const Ray> rays,
                                 size_t stride, const CheckOptions& options, const SceneCase* judge = nullptr,
                                 size_t raySet = 0) {
    Differences d;
    for (size_t i = 0; i < rays.size(); i += stride) {
        const Ray& ray = rays[i];
        ++d.rays;
        QueryCounters counters;
        Hit a, b;
        const bool foundA = updated.findNearest(ray, a, counters), foundB = fresh.findNearest(ray, b, counters);
        const bool occludedA = updated.isOccluded(ray, counters), occludedB = fresh.isOccluded(ray, counters);
        if (foundA == foundB && hitsAgree(a, b) && occludedA == occludedB) continue;
        const auto ambiguous = [&](const Hit& hit) {
            return judge->oracle->judge(ray, hit, judge->reference[raySet].oracle[i]).verdict == Verdict::Ambiguous;
        };
        if (judge && (ambiguous(a) || ambiguous(b))) continue;
        if (++d.count <= options.maxExamples)
            d.examples.push_back(fmt::format("ray {}: updated {} (occluded {}), a fresh build {} (occluded {})",
                                             describe(ray), describe(a), occludedA, describe(b), occludedB));
    }
    return d;
}

// The subject built over `original`, then updated to `moved`; null when it has no update. The
// update is given the build's valid set with the moved positions, as its contract asks: a
// primitive that became degenerate stays in it (and must never be hit).
std::unique_ptr<Accelerator> updatedTo(const Subject& subject, const Scene& original, const Scene& moved,
                                       CheckResult& result, const CheckOptions& options) {
    auto accel = buildOn(subject, original, result, options);
    PrimitiveSet prims = moved.primitives();
    prims.valid = original.validPrimitives;
    if (!accel->update(prims)) return nullptr;
    return accel;
}

// `moved` as an update from `original` sees it: only the primitives valid in both. An update keeps
// the build's valid set, so one that stopped being degenerate waits for a build.
Scene validInBoth(Scene moved, const Scene& original) {
    std::vector<uint32_t> valid;
    std::ranges::set_intersection(moved.validPrimitives, original.validPrimitives, std::back_inserter(valid));
    moved.validPrimitives = std::move(valid);
    return moved;
}

// A scene and the same scene moved, for the examples named by the moved one.
struct Motion {
    NamedSceneFactory original, moved;
};

// The agreement scenes moved by movedScene; the user's scenes moved by their own motion (an
// animated scene's frames), a still one by movedScene.
std::vector<Motion> motions(const CheckOptions& options) {
    std::vector<Motion> list;
    const auto byMovedScene = [&](const NamedSceneFactory& f) {
        list.push_back({f, {"moved " + f.name, [make = f.make] { return movedScene(make()); }}});
    };
    for (const NamedSceneFactory& f : agreementScenes()) byMovedScene(f);
    const std::vector<NamedSceneFactory> users = userScenes(options);
    for (size_t i = 0; i < users.size(); ++i) {
        const NamedSceneFactory& moved = options.scenes[i].moved;
        if (!moved.make) {
            byMovedScene(users[i]);
            continue;
        }
        list.push_back({users[i], {moved.name, [original = users[i].make, make = moved.make] {
                                       return validInBoth(trianglesOf(make()), original());
                                   }}});
    }
    return list;
}

struct Tally {
    size_t reported = 0;  // an external structure's deviations within kExternalBound
    bool noUpdate = false;

    // Failures of one ray set: counted with their examples, or reported for an external
    // structure within its bound.
    void add(const Subject& subject, size_t failures, size_t rays, const std::vector<std::string>& examples,
             const std::string& label, const CheckOptions& options, CheckResult& result) {
        if (isExternal(subject.name) && double(failures) <= kExternalBound * double(rays)) {
            reported += failures;
            return;
        }
        result.failures += failures;
        for (const std::string& e : examples) addExample(result, options, label, e);
    }
};

// The agreement check's scenes and the user's, moved: each ray set (a quarter of the agreement
// check's rays: the reference's answers, computed once per process, are most of the check's time)
// against the oracle of the moved scene and against a fresh build over it.
void checkAgreementAfterUpdate(const Subject& subject, const CheckOptions& options, CheckResult& result, Tally& tally) {
    const std::vector<Motion> all = motions(options);
    for (const Motion& motion : all) {
        const SceneCase& c = sceneCase(motion.moved, {}, 0.25 * options.rayScale, true);
        const Scene original = motion.original.make();
        const auto updated = updatedTo(subject, original, c.scene, result, options);
        if (!updated) {
            tally.noUpdate = true;
            return;
        }
        const auto fresh = buildOn(subject, c.scene, result, options);
        ++result.scenes;
        for (size_t k = 0; k < c.rays.size(); ++k) {
            const auto& [kind, rays] = c.rays[k];
            const std::string label = fmt::format("{}/{}", motion.moved.name, rayKindName(kind));
            const ComparisonReport r =
                compareWithReference(*updated, c.reference[k], *c.oracle, rays, options.maxExamples, true);
            result.cases += r.rays;
            std::vector<std::string> examples = r.examples;
            examples.insert(examples.end(), r.occlusionExamples.begin(), r.occlusionExamples.end());
            tally.add(subject, r.nearestFailures() + r.occlusionFailures(), r.rays, examples, label, options, result);
            // Every second ray: the reference has judged them all. Ours answer as a fresh build
            // whatever the tree; an external structure's float test at edges and vertices may go
            // either way in either tree (Embree's, robust or not), which the reference accepts.
            const Differences d = differencesFromFresh(*updated, *fresh, rays, 2, options, &c, k);
            if (isExternal(subject.name))
                tally.reported += d.count;
            else
                tally.add(subject, d.count, d.rays, d.examples, label, options, result);
        }
        reportProgress(options, result.scenes, all.size() + 2);
    }
}

// Spheres and cones among triangles (the oracle's are triangles only): against a fresh build.
void checkQuadricsAfterUpdate(const Subject& subject, const CheckOptions& options, CheckResult& result, Tally& tally) {
    const Scene original = makeMixedScene(7), moved = movedScene(original);
    const auto updated = updatedTo(subject, original, moved, result, options);
    if (!updated) {
        tally.noUpdate = true;
        return;
    }
    const auto fresh = buildOn(subject, moved, result, options);
    ++result.scenes;
    uint32_t seed = 53;
    for (RayKind kind : {RayKind::Outside, RayKind::Inside}) {
        const size_t count = scaled(raysPerKind(moved, kind), options);
        const std::vector<Ray> rays = generateRays(kind, moved.primitives(), moved.bounds, count, ++seed);
        result.cases += rays.size();
        const Differences d = differencesFromFresh(*updated, *fresh, rays, 1, options);
        tally.add(subject, d.count, d.rays, d.examples, fmt::format("moved mixed/{}", rayKindName(kind)), options,
                  result);
    }
}

// The watertight check's closed meshes, moved (still closed): no probe of the moved mesh leaks.
void checkLeaksAfterUpdate(const Subject& subject, const CheckOptions& options, CheckResult& result, Tally& tally) {
    const ProbedMeshes& original = probedMeshes(options, 3000, false);
    const ProbedMeshes& moved = probedMeshes(options, 3000, true);
    for (size_t m = 0; m < moved.size(); ++m) {
        const auto& [scene, probes] = moved[m];
        const auto updated = updatedTo(subject, original[m].first, scene, result, options);
        if (!updated) {
            tally.noUpdate = true;
            return;
        }
        ++result.scenes;
        tallyLeaks(subject, options, scene, countLeaks(*updated, probes.probes, options.threads, options.maxExamples),
                   result, tally.reported);
    }
}

}  // namespace

CheckResult update(const Subject& subject, const CheckOptions& options) {
    CheckResult result = newResult("update");
    Tally tally;
    checkAgreementAfterUpdate(subject, options, result, tally);
    if (!tally.noUpdate) checkQuadricsAfterUpdate(subject, options, result, tally);
    if (!tally.noUpdate) checkLeaksAfterUpdate(subject, options, result, tally);
    if (tally.noUpdate) {
        result = newResult("update");
        result.skipped = true;
        result.note = fmt::format("{} has no update: its callers build it again", subject.name);
        return result;
    }
    if (tally.reported) result.note = fmt::format("{} known deviations and leaks reported, not failed", tally.reported);
    return result;
}

}  // namespace bvhlab::verify
