// The interface's batch queries (Accelerator::findNearestBatch, isOccludedBatch) for every
// registered accelerator: a render through the batch calls (each wavefront, the shadow rays per
// light) equal to one through the single-ray calls. That the batch calls answer as the single-ray
// ones (bit for bit for ours; Embree's stream kernels round differently from rtcIntersect1, so its
// batch is held to hitsAgree, docs/accuracy.md), count the same (packets: the same queries) and
// add up their per-ray costs is
// the conformance suite's batch check (accel/verify/conformance.h, tests/accel/verify/test_conformance.cpp).
#include "accel/registry.h"
#include "accel/verify/conformance.h"
#include "accel/verify/generated_scenes.h"
#include "accel/verify/verify_keys.h"
#include "framework/render/camera.h"
#include "framework/render/renderer.h"
#include "framework/scene/procedural.h"
#include "tests/support/registered_accelerators.h"

#include <gtest/gtest.h>

namespace bvhlab {
namespace {

using verify::sameCounters;

// An accelerator seen through its single-ray calls only: the interface's default batch loop.
class SingleRayCalls final : public Accelerator {
public:
    explicit SingleRayCalls(const Accelerator& inner) : inner_(inner) {}
    const char* name() const override { return inner_.name(); }
    void build(const PrimitiveSet&) override {}
    void statistics(BuildStatistics&) const override {}
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override {
        return inner_.findNearest(ray, hit, counters);
    }
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override { return inner_.isOccluded(ray, counters); }
    bool hasCounters() const override { return inner_.hasCounters(); }

private:
    const Accelerator& inner_;
};

class BatchQueries : public testing::TestWithParam<std::string> {
protected:
    BatchQueries() : env_(verify::verifyKeys()) {}
    std::unique_ptr<Accelerator> built(const Scene& scene) {
        auto accel = createAccelerator(GetParam(), env_);
        accel->build(scene.primitives());
        return accel;
    }

    Env env_;
};

TEST_P(BatchQueries, RenderAsThroughTheSingleRayCalls) {
    const Scene scene = verify::makeBatchScene();
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
    // Packets (the wide layouts) count each ray's work in the packet's visit order.
    const bool packets = verify::batchTracesPackets(GetParam());
    const auto same = packets ? verify::sameQueries : sameCounters;
    EXPECT_TRUE(same(a.primary.counters, b.primary.counters));
    EXPECT_TRUE(same(a.shadow.counters, b.shadow.counters));
    EXPECT_GT(a.shadow.counters.queries, 0u);
    if (!verify::batchIsBitExact(GetParam())) {
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
        if (packets) continue;
        ASSERT_EQ(viaBatch.traversalSteps[p], viaSingle.traversalSteps[p]) << GetParam() << " pixel " << p;
        ASSERT_EQ(viaBatch.intersectionTests[p], viaSingle.intersectionTests[p]) << GetParam() << " pixel " << p;
    }
}

INSTANTIATE_TEST_SUITE_P(Registered, BatchQueries, testing::ValuesIn(test::registeredAccelerators()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace bvhlab
