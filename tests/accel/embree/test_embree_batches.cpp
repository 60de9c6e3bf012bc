// Embree's batch paths answer as its single-ray call: the bare loop bench times as embree-bare,
// and its stream and packet APIs (embree-batch).
#include "accel/embree/embree_accelerator.h"
#include "accel/verify/ray_generators.h"
#include "framework/render/camera.h"
#include "tests/accel/embree/embree_test_scenes.h"

#include <gtest/gtest.h>

#include <random>

namespace bvhlab {
namespace {

using test::smallScene;

// The bare loop (bench's embree-bare) answers as the interface does on rays Embree takes as
// they are, pass after pass (reset restores what the previous pass wrote into the rays), and
// refuses the rays only the interface's two-segment form can trace.
TEST(Embree, NativeBatchAnswersAsTheInterface) {
    const Scene scene = smallScene();
    EmbreeAccelerator accel;
    accel.build(scene.primitives());
    std::vector<Ray> rays = verify::generateRays(verify::RayKind::Outside, scene.primitives(), scene.bounds, 2000, 5u);
    for (Ray& ray : rays) ray.tmax = 4.0f;  // some rays end before what they would hit
    size_t nearest = 0, occluded = 0;
    QueryCounters counters;
    for (const Ray& ray : rays) {
        Hit hit;
        nearest += accel.findNearest(ray, hit, counters);
        occluded += accel.isOccluded(ray, counters);
    }
    ASSERT_GT(nearest, rays.size() / 10);
    ASSERT_LT(nearest, rays.size());
    const std::unique_ptr<NativeRayBatch> batch = accel.prepareNativeBatch(rays);
    ASSERT_EQ(batch->size(), rays.size());
    for (bool anyHit : {false, true, false}) {
        batch->reset();
        const size_t half = rays.size() / 2;
        EXPECT_EQ(batch->trace(0, half, anyHit) + batch->trace(half, rays.size(), anyHit), anyHit ? occluded : nearest);
    }

    std::vector<Ray> behind = {rays[0]};
    behind[0].tmin = -1.0f;
    EXPECT_THROW(accel.prepareNativeBatch(behind), std::invalid_argument);
}

// Embree's batch APIs (bench's embree-batch: its stream, and its packets of the widths the device
// traces natively) answer the prepared rays as its single-ray call does: closest hits within
// hitsAgree, occlusion equal; on a camera's primary rays (hinted coherent) and on incoherent
// ones, in ranges of 4096 as the bench traces them, pass after pass.
TEST(Embree, BatchApisAnswerAsTheSingleRayCall) {
    const Scene scene = smallScene();
    EmbreeAccelerator accel;
    accel.build(scene.primitives());
    const std::vector<std::string> apis = accel.batchApis();
    ASSERT_FALSE(apis.empty());
    EXPECT_EQ(apis[0], "stream");
    const Camera camera(framingCamera(scene.bounds, 60.0f, 101, 83));  // 8383 rays: a partial packet and range
    std::vector<Ray> primary;
    for (int y = 0; y < camera.height(); ++y)
        for (int x = 0; x < camera.width(); ++x) primary.push_back(camera.generateRay(x + 0.5f, y + 0.5f));
    // Random directions from inside the scene, as short as ambient-occlusion rays: some miss.
    std::vector<Ray> incoherent =
        verify::generateRays(verify::RayKind::Inside, scene.primitives(), scene.bounds, primary.size(), 3u);
    const float aoRadius = 0.3f * glm::length(scene.bounds.diagonal());
    for (Ray& ray : incoherent) ray.tmax = aoRadius / glm::length(ray.dir);
    struct Case {
        const char* name;
        const std::vector<Ray>* rays;
        bool coherent;
    };
    for (const Case& c : {Case{"primary", &primary, true}, Case{"incoherent", &incoherent, false}}) {
        const std::vector<Ray>& rays = *c.rays;
        const std::unique_ptr<EmbreePreparedRays> single = accel.prepareRays(rays, "single", false);
        for (bool anyHit : {false, true}) {
            single->reset();
            const size_t hits = single->trace(0, rays.size(), anyHit);
            ASSERT_GT(hits, rays.size() / 20) << c.name;
            ASSERT_LT(hits, rays.size()) << c.name;
            for (const std::string& api : apis) {
                SCOPED_TRACE(::testing::Message() << c.name << " " << api << (anyHit ? " any hit" : " closest"));
                const std::unique_ptr<EmbreePreparedRays> batch = accel.prepareRays(rays, api, c.coherent);
                ASSERT_EQ(batch->size(), rays.size());
                for (int pass = 0; pass < 2; ++pass) {
                    batch->reset();
                    size_t batchHits = 0;
                    for (size_t begin = 0; begin < rays.size(); begin += 4096)
                        batchHits += batch->trace(begin, std::min(rays.size(), begin + 4096), anyHit);
                    size_t disagree = 0;
                    for (size_t i = 0; i < rays.size(); ++i) {
                        const Hit a = single->hit(i) ? Hit{single->t(i), 0} : Hit{};
                        const Hit b = batch->hit(i) ? Hit{batch->t(i), 0} : Hit{};
                        disagree += anyHit ? a.found() != b.found() : !hitsAgree(a, b);
                    }
                    EXPECT_EQ(disagree, 0u);
                    EXPECT_EQ(batchHits, hits);
                }
            }
        }
    }
    if (apis.size() > 1) {  // a packet range must start on a packet
        const std::unique_ptr<EmbreePreparedRays> packets = accel.prepareRays(primary, apis[1], true);
        EXPECT_THROW(packets->trace(1, 9, false), std::logic_error);
    }
    EXPECT_THROW(accel.prepareRays(primary, "packet4", true), std::invalid_argument);
}

}  // namespace
}  // namespace bvhlab
