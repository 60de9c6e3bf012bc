// The counting split of the ray loops (apps/runtime/trace_rays.h, timing.h): answers with
// QueryCounters::counting off equal those with it on, bit for bit, for structures of ours; the
// counts a loop reports are its counting pass's; its timed passes count nothing.
#include "accel/registry.h"
#include "accel/verify/conformance.h"
#include "accel/verify/generated_scenes.h"
#include "apps/runtime/program_keys.h"
#include "apps/runtime/timing.h"
#include "apps/runtime/trace_rays.h"
#include "framework/render/camera.h"
#include "framework/scene/procedural.h"
#include "framework/scene/surface_point.h"
#include "tests/support/counting_spy.h"

#include <fmt/core.h>
#include <gtest/gtest.h>

#include <cstring>

namespace bvhlab {
namespace {

using test::CountingSpy;

// Rays of one kind of query over a scene.
struct RaySet {
    const char* name;
    const Scene* scene;
    std::vector<Ray> rays;
    bool anyHit;
};

// The embedded scene (triangles only: the wide layouts trace packets) seen by a small camera,
// and the shadow rays toward its first light from the hits.
struct DefaultSceneRays {
    Scene scene = makeDefaultScene();
    std::vector<Ray> primary, shadow;

    DefaultSceneRays() {
        CameraSpec spec = *scene.camera;
        spec.width = 64;
        spec.height = 48;
        const Camera camera(spec);
        for (int y = 0; y < spec.height; ++y)
            for (int x = 0; x < spec.width; ++x)
                primary.push_back(camera.generateRay(float(x) + 0.5f, float(y) + 0.5f));
        const auto naive = createAccelerator("naive", Env(programKeys()));
        naive->build(scene.primitives());
        std::vector<Hit> hits(primary.size());
        QueryCounters unused;
        naive->findNearestBatch(primary, hits, unused, {}, RayCoherence::Coherent);
        for (size_t i = 0; i < primary.size(); ++i) {
            if (!hits[i].found()) continue;
            const Vec3 origin = surfaceAt(scene, primary[i], hits[i]).originAbove();
            shadow.push_back({origin, scene.lights.at(0).position - origin, 0.0f, 1.0f - 1e-5f});
        }
    }
};

const DefaultSceneRays& defaultSceneRays() {
    static const DefaultSceneRays rays;
    return rays;
}

// Primary and shadow rays of the embedded scene; random, axis-parallel, behind-the-origin, empty
// and NaN rays over the batch check's scene of triangles, spheres and cones.
std::vector<RaySet> raySets() {
    static const Scene batchScene = verify::makeBatchScene();
    const DefaultSceneRays& d = defaultSceneRays();
    const std::vector<Ray> mixed = verify::makeBatchRays();
    return {{"primary", &d.scene, d.primary, false},
            {"shadow", &d.scene, d.shadow, true},
            {"mixed closest", &batchScene, mixed, false},
            {"mixed any", &batchScene, mixed, true}};
}

std::unique_ptr<Accelerator> builtOver(const std::string& name, const Scene& scene) {
    auto accel = createAccelerator(name, Env(programKeys()));
    accel->build(scene.primitives());
    return accel;
}

template <typename T>
bool bitEqual(const std::vector<T>& a, const std::vector<T>& b) {
    // memcmp must not see the null data() of an empty vector, even for 0 bytes.
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

class CountingForm : public testing::TestWithParam<std::string> {};

// Through the batch loop of raycast and Python, and ray by ray.
TEST_P(CountingForm, AnswersBitForBitWithCountingOnAndOff) {
    for (const RaySet& set : raySets()) {
        SCOPED_TRACE(set.name);
        const auto accel = builtOver(GetParam(), *set.scene);
        const size_t n = set.rays.size();
        std::vector<Hit> hitsOff(n), hitsOn(n);
        std::vector<uint8_t> occludedOff(set.anyHit ? n : 0), occludedOn(set.anyHit ? n : 0);
        const QueryCounters off = traceRays(*accel, set.rays, set.anyHit, RayCoherence::Coherent, 2, /*counting=*/false,
                                            {hitsOff, occludedOff, {}});
        const QueryCounters on = traceRays(*accel, set.rays, set.anyHit, RayCoherence::Coherent, 2, /*counting=*/true,
                                           {hitsOn, occludedOn, {}});
        EXPECT_TRUE(bitEqual(hitsOff, hitsOn));
        EXPECT_TRUE(bitEqual(occludedOff, occludedOn));
        EXPECT_EQ(off.queries, n);
        EXPECT_EQ(on.queries, n);
        EXPECT_GT(on.traversalSteps + on.intersectionTests, 0u);

        std::vector<Hit> singleOff(n), singleOn(n);
        std::vector<uint8_t> singleOccludedOff(n), singleOccludedOn(n);
        QueryCounters countingOff{.counting = false}, countingOn;
        for (size_t i = 0; i < n; ++i) {
            if (set.anyHit) {
                singleOccludedOff[i] = accel->isOccluded(set.rays[i], countingOff);
                singleOccludedOn[i] = accel->isOccluded(set.rays[i], countingOn);
            } else {
                accel->findNearest(set.rays[i], singleOff[i], countingOff);
                accel->findNearest(set.rays[i], singleOn[i], countingOn);
            }
        }
        EXPECT_TRUE(bitEqual(singleOff, singleOn));
        EXPECT_TRUE(bitEqual(singleOccludedOff, singleOccludedOn));
        EXPECT_TRUE(set.anyHit ? bitEqual(singleOccludedOn, occludedOn) : bitEqual(singleOn, hitsOn));
    }
}

INSTANTIATE_TEST_SUITE_P(Ours, CountingForm, testing::Values("sahbvh8", "sahbvh", "naive"));

// A pass with counting off reports its queries and nothing of the numbers the structure left.
TEST(TraceRays, ReportsOnlyQueriesWithCountingOff) {
    const DefaultSceneRays& d = defaultSceneRays();
    const auto accel = builtOver("sahbvh8", d.scene);
    const CountingSpy spy(*accel);
    std::vector<Hit> hits(d.primary.size());
    const QueryCounters off =
        traceRays(spy, d.primary, false, RayCoherence::Coherent, 2, /*counting=*/false, {hits, {}, {}});
    EXPECT_EQ(off.queries, d.primary.size());
    EXPECT_EQ(off.intersectionTests, 0u);
    EXPECT_EQ(off.traversalSteps, 0u);
    EXPECT_EQ(spy.uncountedRays(), d.primary.size());
    EXPECT_EQ(spy.countedRays(), 0u);
    const QueryCounters on =
        traceRays(spy, d.primary, false, RayCoherence::Coherent, 2, /*counting=*/true, {hits, {}, {}});
    EXPECT_EQ(on.intersectionTests, spy.countedIntersectionTests());
    EXPECT_EQ(on.traversalSteps, spy.countedTraversalSteps());
}

// bench, tradeoff and builders: the timed passes count nothing, and the N_IT and N_TR reported are
// a counting pass's over the same rays in the same ranges (a batch traced as packets counts by its
// ranges), asked as the timed passes were.
TEST(TracePasses, TimesWithCountingOffAndCountsInAPassOfItsOwn) {
    const DefaultSceneRays& d = defaultSceneRays();
    const auto accel = builtOver("sahbvh8", d.scene);
    for (const QueryKind kind : {QueryKind::Single, QueryKind::Batch})
        for (const bool anyHit : {false, true}) {
            SCOPED_TRACE(fmt::format("{} {}", toString(kind), anyHit ? "any-hit" : "closest-hit"));
            const std::vector<Ray>& rays = anyHit ? d.shadow : d.primary;
            const CountingSpy spy(*accel);
            const PassResult r = tracePasses(spy, rays, anyHit, RayCoherence::Coherent, 2, 3, kind);
            EXPECT_EQ(spy.uncountedRays(), 3 * rays.size());
            EXPECT_EQ(spy.countedRays(), rays.size());
            EXPECT_EQ(r.counters.queries, rays.size());
            EXPECT_EQ(r.counters.intersectionTests, spy.countedIntersectionTests());
            EXPECT_EQ(r.counters.traversalSteps, spy.countedTraversalSteps());

            // The counting pass's counts, made here range by range on one thread.
            QueryCounters expected;
            std::vector<Hit> hits(kQueryRange);
            std::vector<uint8_t> occluded(kQueryRange);
            for (size_t begin = 0; begin < rays.size(); begin += kQueryRange) {
                const auto range = std::span(rays).subspan(begin, std::min(kQueryRange, rays.size() - begin));
                if (kind == QueryKind::Single) {
                    for (size_t i = 0; i < range.size(); ++i)
                        if (anyHit)
                            accel->isOccluded(range[i], expected);
                        else
                            accel->findNearest(range[i], hits[i], expected);
                } else if (anyHit) {
                    accel->isOccludedBatch(range, std::span(occluded).first(range.size()), expected, {},
                                           RayCoherence::Coherent);
                } else {
                    accel->findNearestBatch(range, std::span(hits).first(range.size()), expected, {},
                                            RayCoherence::Coherent);
                }
            }
            EXPECT_TRUE(verify::sameCounters(r.counters, expected));
            EXPECT_GT(expected.traversalSteps, 0u);

            const CountingSpy uncounted(*accel);
            const PassResult timedOnly =
                tracePasses(uncounted, rays, anyHit, RayCoherence::Coherent, 2, 2, kind, /*count=*/false);
            EXPECT_EQ(uncounted.countedRays(), 0u);
            EXPECT_EQ(timedOnly.counters.queries, rays.size());
            EXPECT_EQ(timedOnly.counters.intersectionTests, 0u);
        }
}

}  // namespace
}  // namespace bvhlab
