// The reference of the conformance suite (`bvhlab check`, apps/check/conformance.h), also used
// by the accelerator tests: a double-precision brute-force oracle,
// a judge that decides whether an answer is right, wrong, or within rounding of the truth,
// deterministic ray and scene generators, and the comparison of an accelerator against naive.
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
#include <functional>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <vector>

namespace bvhlab::check {

// ---------------------------------------------------------------------------------------------
// Double-precision brute force.

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

// ---------------------------------------------------------------------------------------------
// Ray generators. All deterministic for a given seed (StressRng, framework/robustness/stress_rng.h).

enum class RayKind {
    Outside,       // origins outside the scene bounds, aimed at random points inside them
    Inside,        // origins inside the bounds, random directions
    EdgeAimed,     // aimed at lerp(va, vb, s) of a triangle edge, from random distances
    VertexAimed,   // aimed exactly at a vertex
    AxisParallel,  // direction exactly +-x/+-y/+-z; origins random or at vertex coordinates
    Grazing,       // direction within 1e-6..1e-1 rad of a triangle's plane (sometimes 0)
    Interval,      // very short rays (tmax tiny, hit just inside or outside), tmin > 0,
                   // tmin == tmax, negative tmin, tmin > tmax
    Invalid,       // NaN in any component, zero direction: must miss, must not crash
};
inline constexpr RayKind kAllRayKinds[] = {RayKind::Outside,      RayKind::Inside,   RayKind::EdgeAimed,
                                           RayKind::VertexAimed,  RayKind::AxisParallel, RayKind::Grazing,
                                           RayKind::Interval,     RayKind::Invalid};
const char* rayKindName(RayKind kind);

// How many rays of `kind` the correctness checks send at `scene`: scenes are at most ~10k
// triangles, so the oracle stays at O(1e8) tests.
size_t raysPerKind(const Scene& scene, RayKind kind);

// `bounds` is where random rays are aimed (an empty box is replaced by [-1,1]^3). Kinds that
// need triangles fall back to Outside rays when prims has no valid one.
std::vector<Ray> generateRays(RayKind kind, const PrimitiveSet& prims, const Bounds3& bounds, size_t count,
                              uint32_t seed);

// Watertightness probes for a closed mesh: rays from outside, through a point on an interior
// edge (or a vertex), entering the solid there (the direction makes an angle of at least
// ~11 degrees with every adjacent face). `interiorPointNear(p)` returns a point inside the
// solid near surface point p (it orients the faces). Every such ray must hit, at t <= 1 + slack
// (the ray is p - org, so t = 1 at p). `convex` allows far origins; otherwise they stay close.
struct WatertightProbe {
    Ray ray;
    double maxT;  // 1 + an error bound; a hit farther than this went through the surface
    bool atVertex;
};
std::vector<WatertightProbe> watertightProbes(const Scene& closedMesh, const std::function<Vec3(const Vec3&)>& interiorPointNear,
                                              bool convex, size_t perEdge, size_t perVertex, uint32_t seed);

// ---------------------------------------------------------------------------------------------
// Scene generators. Each returns a finalized scene.

Scene makeSoupScene(size_t count, uint32_t seed, float minSize = 1e-6f, float maxSize = 1e3f, float extent = 100.0f);
Scene makeClosedMeshesScene();  // an icosphere, a box and a torus, disjoint
Scene makeTerrainScene(int cells, uint32_t seed);  // cells x cells height field, 2 triangles per cell
// The cost check's scene, about 32,000 triangles of sizes and densities as different as a
// rendered scene's: a large floor, boxes, a finely tessellated sphere and torus, small
// triangles scattered in the air.
Scene makeCostScene();
Scene makeCoincidentScene(uint32_t seed);  // duplicated triangles (both windings), overlapping coplanar ones
Scene makeCentroidsOnLineScene(size_t count, uint32_t seed);
Scene makeCentroidsOnPlaneScene(size_t count, uint32_t seed);
Scene makeCentroidsAtPointScene(size_t count, uint32_t seed);
Scene makeTinyScene(int triangles, uint32_t seed);  // 0, 1, 2 or 3 triangles
// A soup with degenerate triangles (points, exact segments, repeated vertices, NaN and infinite
// vertices) mixed in at random places.
Scene makeDegenerateMixScene(size_t count, uint32_t seed);

// A scene built from explicit triangles (three positions each), finalized.
Scene sceneFromTriangles(const std::vector<Triangle>& triangles, const std::string& name);

struct NamedSceneFactory {
    std::string name;
    std::function<Scene()> make;
};
// Every generated scene the correctness suite runs, each at most ~10k triangles.
const std::vector<NamedSceneFactory>& generatedScenes();

// ---------------------------------------------------------------------------------------------
// Comparison of an accelerator against naive (and the oracle).

// What naive and the oracle answer on a ray set; computed once, shared by every accelerator.
struct Reference {
    std::vector<Hit> naive;            // naive findNearest
    std::vector<Verdict> naiveVerdict; // the judge on naive's answer
    std::vector<std::string> naiveReason;
    std::vector<OracleHit> oracle;     // double brute-force nearest
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
    size_t returnMismatch = 0;     // return value != hit.found(), or `hit` modified on a miss
    size_t occlusionMismatch = 0;  // isOccluded != findNearest found (outside the tie caveat)
    size_t occlusionTies = 0;      // skipped by the tie caveat
    size_t shrunkOcclusion = 0;    // isOccluded true with tmax just below the nearest t
    size_t queriesMiscounted = 0;  // counters.queries did not go up by exactly 1 per query
    size_t occludedMiscounted = 0; // of them, by isOccluded
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

// Full-precision text for failure messages.
std::string describe(const Ray& ray);
std::string describe(const Hit& hit);
std::string describe(const OracleHit& hit);

}  // namespace bvhlab::check
