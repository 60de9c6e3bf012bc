// The render's counting split (framework/render/renderer.h): every batch (camera rays, mirror
// bounces, the shadow rays of each light) is timed with counting off and counted by a second call
// on the same rays; N_IT, N_TR and the heat maps are the counting calls', the queries each ray
// once, the picture the timed calls'.
#include "accel/registry.h"
#include "accel/verify/verify_keys.h"
#include "framework/render/camera.h"
#include "framework/render/renderer.h"
#include "framework/scene/procedural.h"
#include "tests/support/counting_spy.h"

#include <gtest/gtest.h>

#include <numeric>

namespace bvhlab {
namespace {

using test::CountingSpy;

double sum(const std::vector<float>& values) { return std::accumulate(values.begin(), values.end(), 0.0); }

class RenderCounting : public testing::TestWithParam<std::string> {
protected:
    RenderCounting() : scene_(makeDefaultScene()), accel_(createAccelerator(GetParam(), Env(verify::verifyKeys()))) {
        accel_->build(scene_.primitives());
        spec_ = *scene_.camera;
        spec_.width = 48;
        spec_.height = 32;
        settings_.threads = 2;
        settings_.depthLimit = 2;  // the scene's mirror: a second wavefront
        settings_.lights = scene_.lights;
    }

    RenderStats renderWith(const Accelerator& accel, const RenderSettings& settings, Framebuffer& fb) const {
        return render(scene_, accel, Camera(spec_), settings, fb);
    }

    Scene scene_;
    std::unique_ptr<Accelerator> accel_;
    CameraSpec spec_;
    RenderSettings settings_;
};

TEST_P(RenderCounting, CountsOnlyInTheCountingCalls) {
    const CountingSpy spy(*accel_);
    Framebuffer fb(spec_.width, spec_.height);
    const RenderStats stats = renderWith(spy, settings_, fb);
    const QueryCounters& primary = stats.primary.counters;
    const QueryCounters& shadow = stats.shadow.counters;
    const uint64_t queries = primary.queries + shadow.queries;
    EXPECT_GT(primary.queries, uint64_t(spec_.width * spec_.height));  // bounces too
    EXPECT_GT(shadow.queries, 0u);
    EXPECT_EQ(spy.uncountedRays(), queries);
    EXPECT_EQ(spy.countedRays(), queries);
    EXPECT_EQ(primary.intersectionTests + shadow.intersectionTests, spy.countedIntersectionTests());
    EXPECT_EQ(primary.traversalSteps + shadow.traversalSteps, spy.countedTraversalSteps());
    EXPECT_GT(spy.countedTraversalSteps(), 0u);
    // The heat maps hold every ray's cost of the counting calls.
    EXPECT_EQ(sum(fb.intersectionTests), double(spy.countedIntersectionTests()));
    EXPECT_EQ(sum(fb.traversalSteps), double(spy.countedTraversalSteps()));

    // Without the counting calls: the same picture and queries, nothing counted.
    RenderSettings uncounted = settings_;
    uncounted.count = false;
    const CountingSpy quiet(*accel_);
    Framebuffer quietFb(spec_.width, spec_.height);
    const RenderStats quietStats = renderWith(quiet, uncounted, quietFb);
    EXPECT_EQ(quiet.countedRays(), 0u);
    EXPECT_EQ(quiet.uncountedRays(), queries);
    EXPECT_EQ(quietStats.primary.counters.queries, primary.queries);
    EXPECT_EQ(quietStats.shadow.counters.queries, shadow.queries);
    EXPECT_EQ(quietStats.primary.counters.intersectionTests + quietStats.shadow.counters.traversalSteps, 0u);
    EXPECT_EQ(sum(quietFb.traversalSteps), 0.0);
    EXPECT_EQ(quietFb.color, fb.color);
    EXPECT_EQ(quietFb.primitive, fb.primitive);
    EXPECT_EQ(quietFb.depth, fb.depth);
}

INSTANTIATE_TEST_SUITE_P(Ours, RenderCounting, testing::Values("sahbvh8", "sahbvh", "naive"));

}  // namespace
}  // namespace bvhlab
