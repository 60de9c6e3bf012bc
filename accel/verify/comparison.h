// An accelerator held against naive and the oracle (oracle.h) on a set of rays: the answers
// judged, and the interface contract (return value, isOccluded, query counts) checked.
#pragma once

#include "accel/verify/oracle.h"

#include <span>
#include <string>
#include <vector>

namespace bvhlab::verify {

// What naive and the oracle answer on a ray set; computed once, shared by every accelerator.
struct Reference {
    std::vector<Hit> naive;             // naive findNearest
    std::vector<Verdict> naiveVerdict;  // the judge on naive's answer
    std::vector<std::string> naiveReason;
    std::vector<OracleHit> oracle;  // double brute-force nearest
};
Reference computeReference(const Accelerator& naive, const Oracle& oracle, std::span<const Ray> rays);
// The oracle's answers alone (naive's left empty): the structure is compared with the oracle,
// whose judge decides, and naive is taken to agree with it.
Reference computeOracleReference(const Oracle& oracle, std::span<const Ray> rays);

struct ComparisonReport {
    size_t rays = 0;
    size_t accelHits = 0, naiveHits = 0;
    size_t disagreements = 0;  // !agree(accel, naive)
    // Disagreements with naive, attributed by the oracle's judge:
    size_t accelOnlyWrong = 0;  // the accelerator is wrong, naive is not
    size_t naiveOnlyWrong = 0;  // naive is wrong, the accelerator is not
    size_t bothWrong = 0;
    size_t ambiguous = 0;  // neither is confirmed wrong (rounding at an edge, interval end, grazing)
    // Over all rays, whether or not naive agrees:
    size_t accelWrong = 0;  // the judge says Wrong about the accelerator's answer
    size_t naiveWrong = 0;
    size_t accelVsOracle = 0;  // !agree(accel, oracle), any verdict
    // Interface contract:
    size_t returnMismatch = 0;      // return value != hit.found(), or `hit` modified on a miss
    size_t occlusionMismatch = 0;   // isOccluded != findNearest found (outside the tie caveat)
    size_t occlusionTies = 0;       // skipped by the tie caveat
    size_t shrunkOcclusion = 0;     // isOccluded true with tmax just below the nearest t
    size_t queriesMiscounted = 0;   // counters.queries did not go up by exactly 1 per query
    size_t occludedMiscounted = 0;  // of them, by isOccluded
    // The first few problems, with full ray, t and prim: of findNearest (and the judge), and of isOccluded.
    std::vector<std::string> examples, occlusionExamples;

    size_t failures() const { return nearestFailures() + occlusionFailures(); }
    // What `bvhlab check`'s agreement and any-hit checks count.
    size_t nearestFailures() const { return accelWrong + returnMismatch + queriesMiscounted - occludedMiscounted; }
    size_t occlusionFailures() const { return occlusionMismatch + shrunkOcclusion + occludedMiscounted; }
    std::string summary() const;
};

// With `occlusion` false, isOccluded is not asked; with an empty `reference`, findNearest's
// answers are not judged (the interface contract and isOccluded alone).
ComparisonReport compareWithReference(const Accelerator& accel, const Reference& reference, const Oracle& oracle,
                                      std::span<const Ray> rays, size_t maxExamples = 5, bool occlusion = true);
ComparisonReport compareWithNaive(const Accelerator& accel, const Accelerator& naive, const Oracle& oracle,
                                  std::span<const Ray> rays, size_t maxExamples = 5);

}  // namespace bvhlab::verify
