// The reference of the conformance suite (accel/verify/conformance.h) and of the accelerator
// tests: a double-precision brute-force oracle, and a judge that decides whether an answer is
// right, wrong, or within rounding of the truth.
//
// The oracle runs the framework's own watertight test (intersectTriangle<double>) over every
// valid primitive: the same algorithm as the float one, ~2^29 times more precise. Whether a
// float answer that differs from it is *wrong* or merely *ambiguous* (the ray passes within
// float rounding of an edge, of an interval end, or the t is ill-conditioned at grazing
// incidence) is decided by Oracle::judge with explicit, per-triangle error bounds.
#pragma once

#include "framework/core/accelerator.h"
#include "framework/scene/scene.h"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace bvhlab::verify {

struct OracleHit {
    double t = std::numeric_limits<double>::infinity();
    uint32_t primitive = kInvalidPrimitive;
    double u = 0.0, v = 0.0;

    bool found() const { return primitive != kInvalidPrimitive; }
    Hit toHit() const { return found() ? Hit{float(t), primitive, float(u), float(v)} : Hit{}; }
};

// The agreement every accelerator is held to: the framework's hitsAgree (ray.h).
inline bool agree(const Hit& a, const Hit& b) { return hitsAgree(a, b); }

enum class Verdict { Right, Ambiguous, Wrong };
const char* verdictName(Verdict v);

struct Judgement {
    Verdict verdict = Verdict::Right;
    std::string reason;  // empty when Right
};

class Oracle {
public:
    // Keeps a view of prims: the triangles must outlive the oracle.
    explicit Oracle(const PrimitiveSet& prims);

    // Closest hit over prims.valid in [tmin, tmax] (ties: lowest primitive index); a miss for
    // rays that are not Ray::isValid().
    OracleHit nearest(const Ray& ray) const;
    bool occluded(const Ray& ray) const;
    // Every valid primitive the ray hits in [tmin, tmax], by increasing t.
    std::vector<OracleHit> allHits(const Ray& ray) const;

    // Is `answer` (a float closest-hit answer; !answer.found() = a claimed miss) acceptable?
    //  Wrong     : it claims a primitive that is not valid, a t outside [tmin, tmax], a point
    //              that is not on the claimed triangle (beyond float error bounds), u/v that do
    //              not give that point, or it misses a hit that is unambiguous (away from every
    //              edge and interval end by more than the error bound) and closer than its own.
    //  Ambiguous : it differs from the oracle's nearest hit only within those bounds.
    //  Right     : it agrees (hitsAgree) with the oracle's nearest hit and its claim checks out.
    Judgement judge(const Ray& ray, const Hit& answer) const;
    Judgement judge(const Ray& ray, const Hit& answer, const OracleHit& nearestHit) const;

    bool isValidPrimitive(uint32_t prim) const { return prim < valid_.size() && valid_[prim]; }
    const PrimitiveSet& prims() const { return prims_; }

private:
    PrimitiveSet prims_;
    std::vector<uint8_t> valid_;
};

// Full-precision text for failure messages.
std::string describe(const Ray& ray);
std::string describe(const Hit& hit);
std::string describe(const OracleHit& hit);

}  // namespace bvhlab::verify
