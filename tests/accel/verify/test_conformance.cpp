// The conformance suite (`bvhlab check`, accel/verify/conformance.h) for every registered
// accelerator, one test per check: Registered/CheckSuite.Passes/<accelerator>_<check>. And the
// suite must be able to fail: an accelerator that drops hits fails it, naming a ray. A user's
// animated scene at a frame is checked beside the generated ones, its update to the next frame too.
#include "accel/registry.h"
#include "accel/verify/conformance.h"
#include "accel/verify/conformance_checks.h"
#include "accel/verify/verify_keys.h"
#include "framework/core/error.h"
#include "framework/scene/scene_loader.h"
#include "tests/support/moving_scene.h"
#include "tests/support/scratch_dir.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <tuple>

namespace bvhlab {
namespace {

using Param = std::tuple<std::string, std::string>;  // accelerator, check

std::vector<Param> everyAcceleratorAndCheck() {
    std::vector<Param> params;
    for (const AcceleratorInfo& info : acceleratorInfos())
        for (const std::string& check : verify::checkNames()) params.emplace_back(info.name, check);
    return params;
}

verify::Subject registered(const std::string& name) {
    return {name, [name] { return createAccelerator(name, Env(verify::verifyKeys())); }};
}

std::string report(const verify::CheckResult& r) {
    std::string s =
        fmt::format("{} failures of {} {}{}", r.failures, r.cases, r.unit, r.note.empty() ? "" : " (" + r.note + ")");
    for (const std::string& e : r.examples) s += "\n    " + e;
    return s;
}

// Under AddressSanitizer (tests/sanitize.sh) a quarter of the rays and smaller edge cases: that
// pass looks for memory errors and undefined behaviour, which the same paths show on fewer rays.
verify::CheckOptions suiteOptions() {
    verify::CheckOptions options;
#if defined(__SANITIZE_ADDRESS__)
    options.rayScale = 0.25;
    options.edgePrimitives = 25000;
#endif
    return options;
}

class CheckSuite : public testing::TestWithParam<Param> {};

TEST_P(CheckSuite, Passes) {
    const auto& [accel, check] = GetParam();
    const verify::CheckResult r = verify::runCheck(check, registered(accel), suiteOptions());
    RecordProperty("cases", int(r.cases));
    if (!r.note.empty()) std::printf("[ NOTE     ] %s %s: %s\n", accel.c_str(), check.c_str(), r.note.c_str());
    if (r.skipped) GTEST_SKIP() << r.note;
    EXPECT_GT(r.cases, 0u);
    EXPECT_TRUE(r.passed()) << accel << " fails " << check << ": " << report(r);
}

INSTANTIATE_TEST_SUITE_P(Registered, CheckSuite, testing::ValuesIn(everyAcceleratorAndCheck()),
                         [](const testing::TestParamInfo<Param>& info) {
                             std::string name = std::get<0>(info.param) + "_" + std::get<1>(info.param);
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

// A registered structure that answers every third closest-hit query with a miss.
class DropsEveryThirdHit final : public Accelerator {
public:
    DropsEveryThirdHit() : inner_(createAccelerator("sahbvh", Env(verify::verifyKeys()))) {}
    const char* name() const override { return "drops-hits"; }
    void build(const PrimitiveSet& prims) override { inner_->build(prims); }
    void statistics(BuildStatistics& out) const override { inner_->statistics(out); }
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override {
        if (calls_++ % 3 == 2) {
            ++counters.queries;
            return false;
        }
        return inner_->findNearest(ray, hit, counters);
    }
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override {
        return inner_->isOccluded(ray, counters);
    }

private:
    std::unique_ptr<Accelerator> inner_;
    mutable std::atomic<uint64_t> calls_{0};
};

TEST(CheckSuiteCanFail, AnAcceleratorThatDropsHitsFailsNamingARay) {
    const verify::Subject broken{"drops-hits", [] { return std::make_unique<DropsEveryThirdHit>(); }};
    verify::CheckOptions options;
    options.rayScale = 0.2;
    for (const char* name : {"agreement", "any-hit", "watertight"}) {
        SCOPED_TRACE(name);
        const verify::CheckResult r = verify::runCheck(name, broken, options);
        EXPECT_FALSE(r.passed()) << report(r);
        EXPECT_GT(r.failures, r.cases / 20) << report(r);
        ASSERT_FALSE(r.examples.empty());
        const std::string& example = r.examples.front();
        // The check, the scene, the ray in full precision, and both answers.
        EXPECT_TRUE(example.starts_with(std::string(name) + " on ")) << example;
        EXPECT_NE(example.find("org"), std::string::npos) << example;
        EXPECT_NE(example.find("dir"), std::string::npos) << example;
        EXPECT_NE(example.find("miss"), std::string::npos) << example;
    }
    // The structure it wraps passes the same runs.
    for (const char* name : {"agreement", "any-hit"})
        EXPECT_TRUE(verify::runCheck(name, registered("sahbvh"), options).passed()) << name;
}

// A registered structure whose update claims success and changes nothing: it still answers
// for the primitives where they were built.
class StaleUpdate final : public Accelerator {
public:
    StaleUpdate() : inner_(createAccelerator("sahbvh8", Env(verify::verifyKeys()))) {}
    const char* name() const override { return "stale-update"; }
    void build(const PrimitiveSet& prims) override { inner_->build(prims); }
    bool update(const PrimitiveSet&) override { return true; }
    void statistics(BuildStatistics& out) const override { inner_->statistics(out); }
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override {
        return inner_->findNearest(ray, hit, counters);
    }
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override {
        return inner_->isOccluded(ray, counters);
    }

private:
    std::unique_ptr<Accelerator> inner_;
};

TEST(CheckSuiteCanFail, AnUpdateThatMovesNothingFailsAndNoUpdateIsSkipped) {
    verify::CheckOptions options;
    options.rayScale = 0.2;
    const verify::CheckResult stale =
        verify::runCheck("update", {"stale-update", [] { return std::make_unique<StaleUpdate>(); }}, options);
    EXPECT_GT(stale.failures, stale.cases / 20) << report(stale);
    ASSERT_FALSE(stale.examples.empty());
    EXPECT_TRUE(stale.examples.front().starts_with("update on moved ")) << stale.examples.front();
    const verify::Subject rebuilt{"sahbvh", [] {
                                      Env env(verify::verifyKeys());
                                      env.setOverride("BVH::update=rebuild");
                                      return createAccelerator("sahbvh", env);
                                  }};
    const verify::CheckResult none = verify::runCheck("update", rebuilt, options);
    EXPECT_TRUE(none.skipped) << report(none);
}

// The small animated scene of the tests (a sphere among its triangles) at frame 2, moved to frame 3,
// as `bvhlab check --scene moving.aff -DScene::frame=2` gives it to the checks.
verify::UserScene movingSceneAtFrame2() {
    const auto file = test::scratchDir("conformance") / "moving.aff";
    std::ofstream(file) << test::movingSceneText();
    AnimatedScene animated = loadAnimatedScene(file);
    animated.setTime(animated.frameTime(2));
    const Scene at = animated.scene;
    animated.setTime(animated.frameTime(3));
    const Scene next = animated.scene;
    return {{"moving at frame 2", [at] { return at; }}, {"moving from frame 2 to 3", [next] { return next; }}};
}

TEST(CheckSuiteOnUserScenes, AnAnimatedSceneAtAFrameIsCheckedBesideTheGeneratedOnesAndPasses) {
    verify::CheckOptions options;
    options.rayScale = 0.1;
    options.scenes = {movingSceneAtFrame2()};
    const size_t generated = verify::agreementScenes().size();
    for (const auto& [check, scenes] : {std::pair<std::string, size_t>{"agreement", generated + 1},
                                        {"any-hit", generated + 1},
                                        {"batch", 2},
                                        {"update", generated + 1 + 4}}) {  // + the mixed scene, 3 closed meshes
        SCOPED_TRACE(check);
        const verify::CheckResult r = verify::runCheck(check, registered("sahbvh"), options);
        EXPECT_TRUE(r.passed()) << report(r);
        EXPECT_EQ(r.scenes, scenes) << report(r);
    }
}

TEST(CheckSuiteCanFail, AnUpdateThatMovesNothingFailsOnAnAnimatedSceneMovedToItsNextFrame) {
    verify::CheckOptions options;
    options.rayScale = 0.2;
    options.maxExamples = 1000000;
    options.scenes = {movingSceneAtFrame2()};
    const verify::CheckResult stale =
        verify::runCheck("update", {"stale-update", [] { return std::make_unique<StaleUpdate>(); }}, options);
    EXPECT_TRUE(std::ranges::any_of(stale.examples, [](const std::string& e) {
        return e.starts_with("update on moving from frame 2 to 3/");
    })) << report(stale);
}

TEST(CheckSuiteCanFail, UnknownCheckIsAnInputErrorListingTheKnownOnes) {
    try {
        verify::findCheck("nosuch");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("unknown check 'nosuch'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("agreement"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace bvhlab
