// The verification harness must be able to fail: deliberately broken accelerators (naive's loop
// underneath, one fault each) are caught by the comparison with naive and the oracle, by the
// judge and by the watertightness probes; and the judge decides hand-made answers as it should.
#include <bvhlab/triangle.h>
#include "accel/naive/naive_accelerator.h"
#include "accel/verify/closed_meshes.h"
#include "accel/verify/comparison.h"
#include "accel/verify/generated_scenes.h"
#include "accel/verify/ray_generators.h"
#include "accel/verify/watertight_probe.h"
#include "framework/scene/procedural.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>

namespace bvhlab::verify {
namespace {

// Deliberately broken accelerators (naive's loop underneath, one fault each): the harness must
// catch every one. Without this, a comparison that always passed would go unnoticed.
class FaultyAccelerator final : public BuildStatsAccelerator {
public:
    enum class Fault {
        None,
        DropsTriangles,       // builds over 1 in 50 valid triangles fewer
        ScalesT,              // reports t * 1.01
        WrongPrimitive,       // reports the next valid primitive
        SwapsUV,              // u and v exchanged
        IgnoresTmin,          // clamps tmin to 0
        FarthestHit,          // the farthest hit instead of the nearest
        NeverOccluded,        // isOccluded always false
        OccludedIgnoresTmax,  // isOccluded over [tmin, inf)
        ClobbersHitOnMiss,    // writes a default Hit on a miss
        LeaksAtEdges,         // misses hits within 1e-4 (barycentric) of an edge
        BuildsOverAll,        // ignores PrimitiveSet::valid: degenerate triangles included
    };
    explicit FaultyAccelerator(Fault f) : fault_(f) {}

    const char* name() const override { return "faulty"; }
    void build(const PrimitiveSet& prims) override {
        kept_.clear();
        for (size_t i = 0; i < prims.valid.size(); ++i)
            if (fault_ != Fault::DropsTriangles || i % 50 != 7) kept_.push_back(prims.valid[i]);
        if (fault_ == Fault::BuildsOverAll) {
            kept_.resize(prims.triangles.size());
            for (size_t i = 0; i < kept_.size(); ++i) kept_[i] = uint32_t(i);
        }
        prims_ = {prims.triangles, kept_};
        validCount_ = prims.valid.size();
    }
    BuildStats buildStats() const override {
        BuildStats stats;
        stats.primitives = validCount_;  // what it was given, whatever it kept
        return stats;
    }
    bool findNearest(const Ray& input, Hit& hit, QueryCounters& counters) const override {
        ++counters.queries;
        Ray ray = input;
        if (fault_ == Fault::IgnoresTmin && ray.tmin > 0) ray.tmin = 0;
        Hit best;
        if (ray.isValid()) {
            const ShearedRay sheared(ray);
            for (uint32_t prim : prims_.valid) {
                TriangleHitT<float> h;
                if (!intersectTriangle(sheared, prims_.triangles[prim], ray.tmin, ray.tmax, h)) continue;
                if (fault_ == Fault::LeaksAtEdges && std::min({h.u, h.v, 1.0f - h.u - h.v}) < 1e-4f) continue;
                const bool better = fault_ == Fault::FarthestHit ? (!best.found() || h.t > best.t) : h.t < best.t;
                if (better) best = {h.t, prim, h.u, h.v};
            }
        }
        if (!best.found()) {
            if (fault_ == Fault::ClobbersHitOnMiss) hit = Hit{};
            return false;
        }
        if (fault_ == Fault::ScalesT) best.t *= 1.01f;
        if (fault_ == Fault::SwapsUV) std::swap(best.u, best.v);
        if (fault_ == Fault::WrongPrimitive) {
            const auto it = std::upper_bound(prims_.valid.begin(), prims_.valid.end(), best.primitive);
            best.primitive = it == prims_.valid.end() ? prims_.valid.front() : *it;
        }
        hit = best;
        return true;
    }
    bool isOccluded(const Ray& input, QueryCounters& counters) const override {
        if (fault_ == Fault::NeverOccluded) {
            ++counters.queries;
            return false;
        }
        Ray ray = input;
        if (fault_ == Fault::OccludedIgnoresTmax) ray.tmax = kInfinity;
        Hit hit;
        return findNearest(ray, hit, counters);
    }

private:
    Fault fault_;
    std::vector<uint32_t> kept_;
    PrimitiveSet prims_;
    size_t validCount_ = 0;
};

using Fault = FaultyAccelerator::Fault;

// Runs `fault` over the default scene's rays of `kind` and returns the report.
ComparisonReport runFaulty(Fault fault, RayKind kind, const Scene& scene, size_t rays = 600) {
    NaiveAccelerator naive;
    naive.build(scene.primitives());
    FaultyAccelerator faulty(fault);
    faulty.build(scene.primitives());
    const Oracle oracle(scene.primitives());
    const std::vector<Ray> r = generateRays(kind, scene.primitives(), scene.bounds, rays, 1234);
    return compareWithNaive(faulty, naive, oracle, r);
}

TEST(CorrectnessHarness, PassesAFaithfulReimplementation) {
    const Scene scene = makeDefaultScene();
    for (RayKind kind : kAllRayKinds) {
        const ComparisonReport r = runFaulty(Fault::None, kind, scene, 300);
        EXPECT_EQ(r.failures(), 0u) << rayKindName(kind) << ": " << r.summary();
    }
}

TEST(CorrectnessHarness, CatchesEachInjectedFault) {
    const Scene scene = makeDefaultScene();
    struct Expect {
        Fault fault;
        RayKind kind;
        size_t ComparisonReport::*counter;
        const char* what;
    };
    const Expect cases[] = {
        {Fault::DropsTriangles, RayKind::Outside, &ComparisonReport::accelOnlyWrong, "dropped triangles"},
        {Fault::ScalesT, RayKind::Outside, &ComparisonReport::accelWrong, "t off by 1%"},
        {Fault::WrongPrimitive, RayKind::Outside, &ComparisonReport::accelWrong, "wrong primitive"},
        {Fault::SwapsUV, RayKind::Outside, &ComparisonReport::accelWrong, "u and v swapped"},
        {Fault::IgnoresTmin, RayKind::Interval, &ComparisonReport::accelWrong, "tmin ignored"},
        {Fault::FarthestHit, RayKind::Outside, &ComparisonReport::accelOnlyWrong, "farthest hit"},
        {Fault::NeverOccluded, RayKind::Outside, &ComparisonReport::occlusionMismatch, "isOccluded always false"},
        {Fault::OccludedIgnoresTmax, RayKind::Outside, &ComparisonReport::shrunkOcclusion, "isOccluded past tmax"},
        {Fault::ClobbersHitOnMiss, RayKind::Outside, &ComparisonReport::returnMismatch, "hit written on a miss"},
    };
    for (const Expect& e : cases) {
        const ComparisonReport r = runFaulty(e.fault, e.kind, scene);
        EXPECT_GT(r.*e.counter, 0u) << e.what << " went unnoticed: " << r.summary();
        EXPECT_GT(r.failures(), 0u) << e.what;
        // The faults are the accelerator's: naive must not take the blame.
        EXPECT_EQ(r.naiveWrong, 0u) << e.what << ": " << r.summary();
    }
}

TEST(CorrectnessHarness, CatchesHitsOnDegenerateTriangles) {
    // Exactly collinear triangles are hit by intersectTriangle alone (see
    // Triangle.CollinearTrianglesAreFlaggedDegenerate): an accelerator that builds over every
    // triangle instead of PrimitiveSet::valid reports them, and the judge must object.
    const Scene scene = makeDegenerateMixScene(2000, 12);
    std::vector<Ray> rays;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    for (size_t i = 0; i < scene.triangleCount(); ++i) {
        const Triangle& t = scene.triangles[i];
        if (!isDegenerate(t) || !isFinite(t.v0) || !isFinite(t.v1)) continue;
        for (int k = 0; k < 8; ++k) {
            Ray r;
            r.org = t.v0 + 30.0f * Vec3(U(rng), U(rng), U(rng));
            r.dir = 0.5f * (t.v0 + t.v1) - r.org;
            rays.push_back(r);
        }
    }
    NaiveAccelerator naive;
    naive.build(scene.primitives());
    FaultyAccelerator faulty(Fault::BuildsOverAll);
    faulty.build(scene.primitives());
    const Oracle oracle(scene.primitives());
    const ComparisonReport r = compareWithNaive(faulty, naive, oracle, rays);
    EXPECT_GT(r.accelWrong, 0u) << r.summary();
    EXPECT_EQ(r.naiveWrong, 0u) << r.summary();
    bool mentionsInvalid = false;
    for (const std::string& e : r.examples) mentionsInvalid |= e.find("not a valid") != std::string::npos;
    EXPECT_TRUE(mentionsInvalid) << r.summary();
}

TEST(CorrectnessHarness, WatertightProbesCatchEdgeLeaksAndPassTheOracle) {
    // An accelerator that answers with the double oracle must pass every probe; one that
    // misses hits within 1e-4 of an edge must be caught.
    class OracleAccelerator final : public BuildStatsAccelerator {
    public:
        const char* name() const override { return "oracle"; }
        void build(const PrimitiveSet& prims) override { oracle_ = std::make_unique<Oracle>(prims); }
        BuildStats buildStats() const override { return {}; }
        bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override {
            ++counters.queries;
            const OracleHit h = oracle_->nearest(ray);
            if (h.found()) hit = h.toHit();
            return h.found();
        }
        bool isOccluded(const Ray& ray, QueryCounters& counters) const override {
            ++counters.queries;
            return oracle_->occluded(ray);
        }

    private:
        std::unique_ptr<Oracle> oracle_;
    };
    for (const Scene& mesh : {makeIcosphereMesh(3), makeSubdividedCubeMesh(4), makeTorusMesh(24, 12)}) {
        SCOPED_TRACE(mesh.name);
        ProbeOptions options;
        options.rays = 2000;
        options.seed = 77;
        const std::vector<WatertightProbeRay> probes = makeWatertightProbes(MeshTopology::of(mesh), options).probes;
        OracleAccelerator oracle;
        oracle.build(mesh.primitives());
        const LeakStats good = countLeaks(oracle, probes);
        EXPECT_EQ(good.leaks + good.occlusionLeaks, 0u) << (good.examples.empty() ? "" : good.examples.front());
        FaultyAccelerator leaky(Fault::LeaksAtEdges);
        leaky.build(mesh.primitives());
        const LeakStats bad = countLeaks(leaky, probes);
        EXPECT_GT(bad.leaks, probes.size() / 4) << "an accelerator that leaks at every edge went unnoticed";
    }
}

TEST(CorrectnessHarness, JudgeOnHandMadeAnswers) {
    // Two unit triangles at z = 1 and z = 2; a ray along +z through the interior of both.
    const Scene scene =
        sceneFromTriangles({{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, {{0, 0, 2}, {1, 0, 2}, {0, 1, 2}}}, "two");
    const Oracle oracle(scene.primitives());
    Ray ray;
    ray.org = {0.25f, 0.25f, 0.0f};
    ray.dir = {0, 0, 1};
    const OracleHit truth = oracle.nearest(ray);
    ASSERT_TRUE(truth.found());
    EXPECT_EQ(truth.primitive, 0u);
    EXPECT_DOUBLE_EQ(truth.t, 1.0);
    EXPECT_DOUBLE_EQ(truth.u, 0.25);
    EXPECT_DOUBLE_EQ(truth.v, 0.25);
    EXPECT_EQ(oracle.allHits(ray).size(), 2u);
    EXPECT_TRUE(oracle.occluded(ray));

    EXPECT_EQ(oracle.judge(ray, {1.0f, 0u, 0.25f, 0.25f}).verdict, Verdict::Right);
    EXPECT_EQ(oracle.judge(ray, Hit{}).verdict, Verdict::Wrong);                       // missed
    EXPECT_EQ(oracle.judge(ray, {2.0f, 1u, 0.25f, 0.25f}).verdict, Verdict::Wrong);    // the one behind
    EXPECT_EQ(oracle.judge(ray, {1.0f, 1u, 0.25f, 0.25f}).verdict, Verdict::Wrong);    // wrong primitive
    EXPECT_EQ(oracle.judge(ray, {1.0f, 0u, 0.5f, 0.25f}).verdict, Verdict::Wrong);     // wrong u
    EXPECT_EQ(oracle.judge(ray, {1.001f, 0u, 0.25f, 0.25f}).verdict, Verdict::Wrong);  // wrong t
    EXPECT_EQ(oracle.judge(ray, {1.0f, 7u, 0.25f, 0.25f}).verdict, Verdict::Wrong);    // no such primitive

    // Through the hypotenuse of the first triangle, exactly: missing it is within rounding
    // (ambiguous), provided the triangle behind is reported.
    ray.org = {0.5f, 0.5f, 0.0f};
    EXPECT_EQ(oracle.judge(ray, {2.0f, 1u, 0.5f, 0.5f}).verdict, Verdict::Ambiguous);
    EXPECT_EQ(oracle.judge(ray, {1.0f, 0u, 0.5f, 0.5f}).verdict, Verdict::Right);
    EXPECT_EQ(oracle.judge(ray, Hit{}).verdict, Verdict::Ambiguous);  // both at their edges

    // Invalid rays: any hit is wrong.
    ray.dir = Vec3(0.0f);
    EXPECT_EQ(oracle.judge(ray, Hit{}).verdict, Verdict::Right);
    EXPECT_EQ(oracle.judge(ray, {1.0f, 0u, 0.5f, 0.5f}).verdict, Verdict::Wrong);
}

}  // namespace
}  // namespace bvhlab::verify
