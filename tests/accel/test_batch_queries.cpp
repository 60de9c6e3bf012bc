// The interface's batch queries (Accelerator::findNearestBatch, isOccludedBatch) against its
// single-ray calls, for every registered accelerator: the same answers (bit for bit for ours;
// Embree's stream kernels round differently from rtcIntersect1, so its batch is held to hitsAgree,
// docs/accuracy.md), the same counters, per-ray costs that add up to them; and a render through the
// batch calls (each wavefront, the shadow rays per light) equal to one through the single-ray calls.
#include "accel/registry.h"
#include "apps/common/program_keys.h"
#include "framework/render/camera.h"
#include "framework/render/renderer.h"
#include "framework/scene/procedural.h"
#include "tests/support/random_geometry.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>

namespace bvhlab {
namespace {

using test::randomPointWithin;
using test::randomUnit;

// Triangles (closed meshes and a mirror floor), spheres and cones.
Scene batchScene() {
    Scene scene;
    scene.name = "batch";
    scene.materials = {{Vec3(0.6f), 0.0f}, {Vec3(0.3f), 0.7f}};
    addQuad(scene, Vec3(-6, -2, -6), Vec3(0, 0, 12), Vec3(12, 0, 0), 1);
    addIcosphere(scene, Vec3(-2, 0, 0), 1.5f, 3, 0);
    addBox(scene, Vec3(1, -1, -1), Vec3(3, 1.5f, 1), 0);
    std::mt19937 rng(7);
    for (int i = 0; i < 40; ++i) scene.spheres.push_back({Vec3(randomPointWithin(rng, 5.0)), 0.1f + 0.02f * float(i)});
    for (int i = 0; i < 40; ++i) {
        const Vec3 base(randomPointWithin(rng, 5.0));
        scene.cones.push_back({base, 0.3f, base + Vec3(randomUnit(rng)), i % 2 ? 0.0f : 0.2f});
    }
    scene.finalize();
    return scene;
}

// Random rays, axis-parallel ones, intervals reaching behind the origin, empty ones and NaN.
std::vector<Ray> batchRays() {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    std::vector<Ray> rays;
    for (int i = 0; i < 3000; ++i) {
        const Vec3 org(randomPointWithin(rng, 12.0));
        Ray r{org, Vec3(randomPointWithin(rng, 4.0)) - org};
        if (i % 7 == 0) r.dir = Vec3(0.0f), r.dir[i % 3] = i % 2 ? 1.0f : -1.0f;
        if (i % 5 == 0) r.tmin = -10.0f * U(rng);
        if (i % 11 == 0) r.tmax = 2.0f * U(rng);
        if (i % 13 == 0) r.tmin = 3.0f, r.tmax = 1.0f;
        if (i % 17 == 0) r.org.y = std::numeric_limits<float>::quiet_NaN();
        rays.push_back(r);
    }
    return rays;
}

bool bitEqual(const Hit& a, const Hit& b) { return std::memcmp(&a, &b, sizeof(Hit)) == 0; }

// Embree's batch goes through its stream API, whose rounding is its own (and its ISA's).
bool batchIsBitExact(std::string_view accel) { return !accel.starts_with("embree"); }

bool sameCounters(const QueryCounters& a, const QueryCounters& b) {
    return a.queries == b.queries && a.intersectionTests == b.intersectionTests &&
           a.traversalSteps == b.traversalSteps && a.sphereTests == b.sphereTests && a.coneTests == b.coneTests;
}

// An accelerator seen through its single-ray calls only: the interface's default batch loop.
class SingleRayCalls final : public Accelerator {
public:
    explicit SingleRayCalls(const Accelerator& inner) : inner_(inner) {}
    std::string_view name() const override { return inner_.name(); }
    BuildStats build(const PrimitiveSet&) override { return {}; }
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override {
        return inner_.findNearest(ray, hit, counters);
    }
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override { return inner_.isOccluded(ray, counters); }
    bool hasCounters() const override { return inner_.hasCounters(); }

private:
    const Accelerator& inner_;
};

std::vector<std::string> registeredAccelerators() {
    std::vector<std::string> names;
    for (const AcceleratorInfo& info : acceleratorInfos()) names.push_back(info.name);
    return names;
}

class BatchQueries : public testing::TestWithParam<std::string> {
protected:
    BatchQueries() : env_(programKeys()) {}
    std::unique_ptr<Accelerator> built(const Scene& scene) {
        auto accel = createAccelerator(GetParam(), env_);
        accel->build(scene.primitives());
        return accel;
    }

    Env env_;
};

TEST_P(BatchQueries, AnswerAsTheSingleRayCallsBitForBit) {
    const Scene scene = batchScene();
    const auto accel = built(scene);
    const std::vector<Ray> rays = batchRays();

    QueryCounters single, batch, singleOcc, batchOcc;
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
        accel->findNearestBatch(part, std::span(hits).subspan(begin, n), batch, std::span(costs).subspan(begin, n));
        accel->isOccludedBatch(part, std::span(occluded).subspan(begin, n), batchOcc, std::span(occCosts).subspan(begin, n));
        begin += n;
    }
    const bool exact = batchIsBitExact(GetParam());
    size_t found = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        ASSERT_TRUE(exact ? bitEqual(hits[i], expected[i]) : hitsAgree(hits[i], expected[i])) << GetParam() << " ray " << i << ": t " << hits[i].t << " vs "
                                                    << expected[i].t << ", primitive " << hits[i].primitive << " vs "
                                                    << expected[i].primitive;
        ASSERT_EQ(occluded[i], expectedOcc[i]) << GetParam() << " ray " << i;
        found += expected[i].found();
    }
    EXPECT_GT(found, rays.size() / 4);
    EXPECT_LT(found, rays.size());
    EXPECT_TRUE(sameCounters(batch, single)) << GetParam();
    EXPECT_TRUE(sameCounters(batchOcc, singleOcc)) << GetParam();
    uint64_t tests = 0, steps = 0;
    for (const RayCost& c : costs) tests += c.intersectionTests, steps += c.traversalSteps;
    EXPECT_EQ(tests, batch.intersectionTests);
    EXPECT_EQ(steps, batch.traversalSteps);
    tests = steps = 0;
    for (const RayCost& c : occCosts) tests += c.intersectionTests, steps += c.traversalSteps;
    EXPECT_EQ(tests, batchOcc.intersectionTests);
    EXPECT_EQ(steps, batchOcc.traversalSteps);
}

TEST_P(BatchQueries, RenderAsThroughTheSingleRayCalls) {
    const Scene scene = batchScene();
    const auto accel = built(scene);
    const SingleRayCalls single(*accel);
    CameraSpec spec{Vec3(0, 4, 12), Vec3(0), Vec3(0, 1, 0), 60.0f, 48, 40};
    RenderSettings settings;
    settings.threads = 2;
    settings.samples = 2;
    settings.depthLimit = 3;
    settings.lights = {{Vec3(10, 10, 5), Vec3(1.0f)}, {Vec3(-8, 6, 2), Vec3(0.5f)}};
    Framebuffer viaBatch(spec.width, spec.height), viaSingle(spec.width, spec.height);
    const RenderStats a = render(scene, *accel, Camera(spec), settings, viaBatch);
    const RenderStats b = render(scene, single, Camera(spec), settings, viaSingle);
    EXPECT_TRUE(sameCounters(a.primary.counters, b.primary.counters));
    EXPECT_TRUE(sameCounters(a.shadow.counters, b.shadow.counters));
    EXPECT_GT(a.shadow.counters.queries, 0u);
    if (!batchIsBitExact(GetParam())) {
        // Rounding apart, the same picture: a hit found at a t a few ulps off shades the same.
        size_t differ = 0;
        for (size_t p = 0; p < viaBatch.color.size(); ++p)
            differ += glm::any(glm::greaterThan(glm::abs(viaBatch.color[p] - viaSingle.color[p]), Vec3(1e-3f)));
        EXPECT_LE(differ, viaBatch.color.size() / 200) << GetParam();
        return;
    }
    for (size_t p = 0; p < viaBatch.color.size(); ++p) {
        ASSERT_EQ(viaBatch.color[p], viaSingle.color[p]) << GetParam() << " pixel " << p;
        ASSERT_EQ(viaBatch.primitive[p], viaSingle.primitive[p]) << GetParam() << " pixel " << p;
        ASSERT_EQ(viaBatch.traversalSteps[p], viaSingle.traversalSteps[p]) << GetParam() << " pixel " << p;
        ASSERT_EQ(viaBatch.intersectionTests[p], viaSingle.intersectionTests[p]) << GetParam() << " pixel " << p;
    }
}


INSTANTIATE_TEST_SUITE_P(Registered, BatchQueries, testing::ValuesIn(registeredAccelerators()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace bvhlab
