// The `embree` accelerator's devices: every quality builds, configurations from env, several
// devices alive at once (of different ISAs too), concurrent queries, and the process-wide thread
// limit. Agreement with
// the other accelerators on whole scenes is tested in the cross-accelerator suite.
#include "accel/embree/embree_accelerator.h"
#include "accel/naive/naive_accelerator.h"
#include "accel/registry.h"
#include "accel/verify/verify_keys.h"
#include "framework/core/cpu_levels.h"
#include "framework/core/timed_build.h"
#include "tests/accel/embree/embree_test_scenes.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <fmt/format.h>

#include <random>
#include <thread>

namespace bvhlab {
namespace {

using test::rayAlongZ;
using test::SkippingScene;
using test::smallScene;

// Random rays through a scene, answered by naive and by `accel`.
void expectAgreesWithNaive(const Scene& scene, const Accelerator& accel, int rays, uint32_t seed) {
    NaiveAccelerator naive;
    naive.build(scene.primitives());
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    const Vec3 c = scene.bounds.center(), d = scene.bounds.diagonal();
    QueryCounters counters;
    int hits = 0;
    for (int i = 0; i < rays; ++i) {
        Ray ray;
        ray.org = c + d * Vec3(unit(rng), unit(rng), unit(rng));
        ray.dir = Vec3(unit(rng), unit(rng), unit(rng));
        Hit expected, actual;
        const bool e = naive.findNearest(ray, expected, counters);
        const bool a = accel.findNearest(ray, actual, counters);
        ASSERT_EQ(e, a) << "ray " << i;
        ASSERT_TRUE(hitsAgree(expected, actual)) << "ray " << i << ": t " << expected.t << " vs " << actual.t;
        ASSERT_EQ(naive.isOccluded(ray, counters), accel.isOccluded(ray, counters)) << "ray " << i;
        hits += e;
    }
    EXPECT_GT(hits, rays / 10);
}

TEST(Embree, EveryQualityAndRobustBuilds) {
    const Scene scene = smallScene();
    for (EmbreeQuality quality : {EmbreeQuality::Low, EmbreeQuality::Medium, EmbreeQuality::High}) {
        for (bool robust : {false, true}) {
            SCOPED_TRACE(::testing::Message() << "quality " << int(quality) << " robust " << robust);
            EmbreeConfig config;
            config.quality = quality;
            config.robust = robust;
            EmbreeAccelerator accel(config);
            const BuildStats stats = timedBuild(accel, scene.primitives());
            EXPECT_EQ(stats.primitives, scene.validPrimitives.size());
            expectAgreesWithNaive(scene, accel, 200, 7u);
        }
    }
}

TEST(Embree, ConfigFromEnv) {
    Env env(verify::verifyKeys());
    EmbreeConfig config = EmbreeConfig::fromEnv(env);
    EXPECT_EQ(config.quality, EmbreeQuality::Medium);
    EXPECT_FALSE(config.robust);
    EXPECT_EQ(config.threads, 0);
    EXPECT_EQ(config.maxIsa, "");  // auto: no limit

    env.setOverride("SetRayTracing::threads=1");
    EXPECT_EQ(EmbreeConfig::fromEnv(env).threads, 1);  // follows the render threads
    env.setOverride("Embree::threads=2");
    env.setOverride("Embree::quality=high");
    env.setOverride("Embree::robust=true");
    config = EmbreeConfig::fromEnv(env);
    EXPECT_EQ(config.threads, 2);  // unless set itself
    EXPECT_EQ(config.quality, EmbreeQuality::High);
    EXPECT_TRUE(config.robust);
    EXPECT_THROW(env.setOverride("Embree::quality=ultra"), std::exception);
    EXPECT_THROW(env.setOverride("Embree::isa=avx512skx"), std::exception);  // Embree 3's names only

    env.setOverride("ASDS::type=embree");
    const std::unique_ptr<Accelerator> accel = createAccelerator(env);
    EXPECT_STREQ(accel->name(), "embree");
    EXPECT_EQ(static_cast<const EmbreeAccelerator&>(*accel).deviceConfig(), "threads=2");
    env.setOverride("Embree::isa=sse4.2");
    EXPECT_EQ(EmbreeConfig::fromEnv(env).maxIsa, "sse4.2");
    EXPECT_EQ(static_cast<const EmbreeAccelerator&>(*createAccelerator(env)).deviceConfig(),
              "threads=2,max_isa=sse4.2");
}

// The kernel width a structure reports (its figure kernel_bits).
double kernelBits(const BuildStats& stats) {
    for (const NamedFigure& f : stats.figures)
        if (f.name == "kernel_bits") return f.value;
    return 0;
}

// Embree::isa limits each device on its own: devices of several ISAs alive at once run kernels of
// their own width (never one shared device), each answering within the accuracy rule, and at
// avx2 as the default device does. An ISA above the CPU's is its best, not an error.
TEST(Embree, IsaLimitsEachDevice) {
    const Scene scene = smallScene();
    const CpuLevels cpu = cpuLevels();
    const int best = cpu.v4 ? 512 : cpu.v3 ? 256 : 128;
    const std::pair<const char*, int> isas[] = {
        {"", best}, {"sse2", 128}, {"sse4.2", 128}, {"avx2", std::min(best, 256)}, {"avx512", best}};
    std::vector<std::unique_ptr<EmbreeAccelerator>> devices;
    for (const auto& [isa, bits] : isas) {
        EmbreeConfig config;
        config.maxIsa = isa;
        devices.push_back(std::make_unique<EmbreeAccelerator>(config));
        devices.back()->build(scene.primitives());
        SCOPED_TRACE(devices.back()->deviceConfig());
        EXPECT_EQ(devices.back()->deviceConfig(), *isa ? fmt::format("threads=0,max_isa={}", isa) : "threads=0");
        EXPECT_EQ(devices.back()->kernelBits(), bits);
        EXPECT_EQ(kernelBits(devices.back()->buildStats()), bits);
        expectAgreesWithNaive(scene, *devices.back(), 200, 13u);
    }
    // avx2 against the default device, ray by ray, both alive.
    const EmbreeAccelerator& byDefault = *devices[0];
    const EmbreeAccelerator& avx2 = *devices[3];
    std::mt19937 rng(17u);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    const Vec3 c = scene.bounds.center(), d = scene.bounds.diagonal();
    QueryCounters counters;
    for (int i = 0; i < 500; ++i) {
        const Ray ray{c + d * Vec3(unit(rng), unit(rng), unit(rng)), Vec3(unit(rng), unit(rng), unit(rng))};
        Hit a, b;
        ASSERT_EQ(byDefault.findNearest(ray, a, counters), avx2.findNearest(ray, b, counters)) << "ray " << i;
        ASSERT_TRUE(hitsAgree(a, b)) << "ray " << i << ": t " << a.t << " vs " << b.t;
        ASSERT_EQ(byDefault.isOccluded(ray, counters), avx2.isOccluded(ray, counters)) << "ray " << i;
    }
}

TEST(Embree, TwoAcceleratorsAliveAtOnce) {
    const SkippingScene first;
    const Scene second = smallScene();
    EmbreeConfig oneThread;
    oneThread.threads = 1;
    EmbreeAccelerator a(oneThread);
    EmbreeAccelerator b;  // all threads, high quality
    a.build(first.prims());
    {
        EmbreeConfig high;
        high.quality = EmbreeQuality::High;
        EmbreeAccelerator c(high);
        c.build(second.primitives());
        b.build(second.primitives());
        expectAgreesWithNaive(second, c, 100, 3u);
    }  // c's device released while a and b live
    expectAgreesWithNaive(second, b, 100, 5u);
    QueryCounters counters;
    Hit hit;
    ASSERT_TRUE(a.findNearest(rayAlongZ(0.25f, 0.25f, 3.0f), hit, counters));
    EXPECT_EQ(hit.primitive, 3u);
}

TEST(Embree, ConcurrentQueries) {
    const Scene scene = smallScene();
    EmbreeAccelerator accel;
    accel.build(scene.primitives());
    std::vector<Ray> rays(2000);
    std::mt19937 rng(11u);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (Ray& ray : rays) {
        ray.org = 3.0f * Vec3(unit(rng), unit(rng), unit(rng));
        ray.dir = Vec3(unit(rng), unit(rng), unit(rng));
    }
    std::vector<Hit> expected(rays.size());
    QueryCounters serial;
    for (size_t i = 0; i < rays.size(); ++i) accel.findNearest(rays[i], expected[i], serial);

    constexpr int kThreads = 4;
    std::vector<QueryCounters> counters(kThreads);
    std::vector<int> mismatches(kThreads, 0);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
        threads.emplace_back([&, t] {
            for (int pass = 0; pass < 3; ++pass) {
                for (size_t i = 0; i < rays.size(); ++i) {
                    Hit hit;
                    accel.findNearest(rays[i], hit, counters[t]);
                    if (hit.primitive != expected[i].primitive || hit.t != expected[i].t) ++mismatches[t];
                    accel.isOccluded(rays[i], counters[t]);
                }
            }
        });
    }
    for (std::thread& thread : threads) thread.join();
    for (int t = 0; t < kThreads; ++t) {
        EXPECT_EQ(mismatches[t], 0);
        EXPECT_EQ(counters[t].queries, 2 * 3 * rays.size());
    }
}

// Embree's thread count is process-wide: a device created with threads=N limits all TBB
// parallelism to N while it lives (the largest request among live devices wins).
TEST(Embree, ThreadSettingLimitsTbbWhileTheDeviceLives) {
    using tbb::global_control;
    const size_t before = global_control::active_value(global_control::max_allowed_parallelism);
    {
        EmbreeConfig config;
        config.threads = 1;
        EmbreeAccelerator accel(config);
        EXPECT_EQ(global_control::active_value(global_control::max_allowed_parallelism), 1u);
        {
            EmbreeAccelerator unlimited;  // threads=0: all hardware threads wins over 1
            EXPECT_EQ(global_control::active_value(global_control::max_allowed_parallelism), before);
        }
        EXPECT_EQ(global_control::active_value(global_control::max_allowed_parallelism), 1u);
    }
    EXPECT_EQ(global_control::active_value(global_control::max_allowed_parallelism), before);
}

}  // namespace
}  // namespace bvhlab
