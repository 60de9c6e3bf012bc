#include "accel/verify/comparison.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace bvhlab::verify {

Reference computeReference(const Accelerator& naive, const Oracle& oracle, std::span<const Ray> rays) {
    Reference ref;
    ref.naive.resize(rays.size());
    ref.naiveVerdict.resize(rays.size());
    ref.naiveReason.resize(rays.size());
    ref.oracle.resize(rays.size());
    QueryCounters counters;
    for (size_t i = 0; i < rays.size(); ++i) {
        Hit hit;
        if (!naive.findNearest(rays[i], hit, counters)) hit = Hit{};
        ref.naive[i] = hit;
        ref.oracle[i] = oracle.nearest(rays[i]);
        Judgement j = oracle.judge(rays[i], hit, ref.oracle[i]);
        ref.naiveVerdict[i] = j.verdict;
        ref.naiveReason[i] = std::move(j.reason);
    }
    return ref;
}

Reference computeOracleReference(const Oracle& oracle, std::span<const Ray> rays) {
    Reference ref;
    ref.oracle.resize(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) ref.oracle[i] = oracle.nearest(rays[i]);
    return ref;
}

std::string ComparisonReport::summary() const {
    std::string s = fmt::format(
        "{} rays: accel {} hits, naive {} hits; {} disagreements with naive (accelerator wrong {}, naive wrong {}, "
        "both wrong {}, ambiguous {}); judged wrong overall: accelerator {}, naive {}; accelerator != oracle on {} "
        "rays; return/hit contract violations {}; isOccluded != findNearest {} (+{} skipped as ties at an interval "
        "end); isOccluded true below the nearest hit {}; queries miscounted {}",
        rays, accelHits, naiveHits, disagreements, accelOnlyWrong, naiveOnlyWrong, bothWrong, ambiguous, accelWrong,
        naiveWrong, accelVsOracle, returnMismatch, occlusionMismatch, occlusionTies, shrunkOcclusion,
        queriesMiscounted);
    for (const std::string& e : examples) s += "\n    " + e;
    for (const std::string& e : occlusionExamples) s += "\n    " + e;
    return s;
}

namespace {

// Compares one structure's answers with the reference ray by ray into a report, keeping the first
// few examples of each kind of failure.
struct RayComparison {
    ComparisonReport& report;
    std::span<const Ray> rays;
    size_t maxExamples;

    void exampleIn(std::vector<std::string>& list, size_t i, const std::string& what) const {
        if (list.size() < maxExamples) list.push_back(fmt::format("ray #{} {}: {}", i, describe(rays[i]), what));
    }
    void example(size_t i, const std::string& what) const { exampleIn(report.examples, i, what); }
    void occlusionExample(size_t i, const std::string& what) const { exampleIn(report.occlusionExamples, i, what); }

    // findNearest's answer to ray i (Hit{} for a miss), its return value and count checked
    // against the interface's contract.
    Hit nearest(const Accelerator& accel, size_t i) const {
        const Hit sentinel{-12345.0f, 0xDEADBEEFu, 7.0f, 9.0f};
        QueryCounters counters;
        Hit hit = sentinel;
        const bool found = accel.findNearest(rays[i], hit, counters);
        if (counters.queries != 1) {
            ++report.queriesMiscounted;
            example(i, fmt::format("findNearest counted {} queries", counters.queries));
        }
        if (found ? !hit.found()
                  : (hit.t != sentinel.t || hit.primitive != sentinel.primitive || hit.u != sentinel.u ||
                     hit.v != sentinel.v)) {
            ++report.returnMismatch;
            example(i, fmt::format("findNearest returned {} with hit {}", found, describe(hit)));
        }
        const Hit a = found ? hit : Hit{};
        report.accelHits += a.found();
        return a;
    }

    // The answer `a` to ray i judged against the oracle, and against naive's answer when the
    // reference has it (without it, naive is the oracle).
    void judge(const Reference& ref, const Oracle& oracle, size_t i, const Hit& a) const {
        const bool withNaive = !ref.naive.empty();
        const Hit n = withNaive ? ref.naive[i] : ref.oracle[i].toHit();
        report.naiveHits += n.found();
        const bool naiveWrong = withNaive && ref.naiveVerdict[i] == Verdict::Wrong;
        report.naiveWrong += naiveWrong;

        const Judgement ja = oracle.judge(rays[i], a, ref.oracle[i]);
        const bool accelWrong = ja.verdict == Verdict::Wrong;
        report.accelWrong += accelWrong;
        report.accelVsOracle += !agree(a, ref.oracle[i].toHit());
        if (!agree(a, n)) {
            ++report.disagreements;
            if (accelWrong && naiveWrong)
                ++report.bothWrong;
            else if (accelWrong)
                ++report.accelOnlyWrong;
            else if (naiveWrong)
                ++report.naiveOnlyWrong;
            else
                ++report.ambiguous;
        }
        if (accelWrong && !withNaive)
            example(i, fmt::format("structure {} [{}: {}]; reference {}", describe(a), verdictName(ja.verdict),
                                   ja.reason, describe(ref.oracle[i])));
        else if (accelWrong || naiveWrong)
            example(i,
                    fmt::format("accelerator {} [{}: {}]; naive {} [{}{}{}]; oracle {}", describe(a),
                                verdictName(ja.verdict), ja.reason, describe(n), verdictName(ref.naiveVerdict[i]),
                                naiveWrong ? ": " : "", naiveWrong ? ref.naiveReason[i] : "", describe(ref.oracle[i])));
    }

    // isOccluded must answer "is there a hit" exactly as findNearest did (`a`), except for a hit
    // within hitsAgree's tolerance of an interval end.
    void occlusion(const Accelerator& accel, size_t i, const Hit& a) const {
        const Ray& ray = rays[i];
        QueryCounters occCounters;
        const bool occluded = accel.isOccluded(ray, occCounters);
        if (occCounters.queries != 1) {
            ++report.queriesMiscounted;
            ++report.occludedMiscounted;
            occlusionExample(i, fmt::format("isOccluded counted {} queries", occCounters.queries));
        }
        if (occluded != a.found()) {
            const float tol = 1e-4f * std::max(1.0f, std::abs(a.t));
            const bool tie = a.found() && (std::abs(a.t - ray.tmax) <= tol || std::abs(a.t - ray.tmin) <= tol);
            if (tie) {
                ++report.occlusionTies;
            } else {
                ++report.occlusionMismatch;
                occlusionExample(i, fmt::format("isOccluded = {} but findNearest found {}", occluded, describe(a)));
            }
        }
        // Nothing can block the ray before its nearest hit: with tmax just below the nearest t
        // (by 1e-3 relative, far more than any rounding of t), isOccluded must be false. For
        // accelerators that run the same float triangle test in both queries this is exact.
        if (a.found() && a.t > 0.0f && std::isfinite(a.t)) {
            Ray shorter = ray;
            shorter.tmax = a.t * (1.0f - 1e-3f);
            if (shorter.tmin <= shorter.tmax && accel.isOccluded(shorter, occCounters)) {
                ++report.shrunkOcclusion;
                occlusionExample(i, fmt::format("isOccluded true with tmax = {:.9g} below the nearest hit {}",
                                                shorter.tmax, describe(a)));
            }
        }
    }
};

}  // namespace

ComparisonReport compareWithReference(const Accelerator& accel, const Reference& ref, const Oracle& oracle,
                                      std::span<const Ray> rays, size_t maxExamples, bool occlusion) {
    ComparisonReport report;
    report.rays = rays.size();
    const RayComparison compare{report, rays, maxExamples};
    // Without the oracle's answers (an empty Reference), the interface contract alone.
    const bool judged = !ref.oracle.empty();
    for (size_t i = 0; i < rays.size(); ++i) {
        const Hit a = compare.nearest(accel, i);
        if (judged) compare.judge(ref, oracle, i, a);
        if (occlusion) compare.occlusion(accel, i, a);
    }
    return report;
}

ComparisonReport compareWithNaive(const Accelerator& accel, const Accelerator& naive, const Oracle& oracle,
                                  std::span<const Ray> rays, size_t maxExamples) {
    return compareWithReference(accel, computeReference(naive, oracle, rays), oracle, rays, maxExamples);
}
}  // namespace bvhlab::verify
