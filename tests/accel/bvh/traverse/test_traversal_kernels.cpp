// The traversal kernels compiled per ISA (accel/bvh/traverse/traversal_kernels.h) answer bit
// for bit alike: every kernel this CPU runs against the scalar one, for the binary and both wide
// layouts, single and batch queries (packets, coherent packets and streams), hits (t, primitive,
// u, v) and counters, on random, axis-parallel and grazing rays and rays whose interval starts
// below 0; and each kernel's form that counts nothing answers as its counting form; and the
// wide layouts' single-ray steps (BVH::singleStep) answer alike in every kernel. Kernels the CPU
// cannot run are not run (so this passes on AVX2-only machines) and asking for one is an
// InputError.
#include "accel/bvh/builder_table.h"
#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/bvh_env.h"
#include "accel/registry.h"
#include "accel/verify/verify_keys.h"
#include "framework/core/error.h"
#include "tests/support/bvh_checks.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>

namespace bvhlab {
namespace {

constexpr Isa kIsas[] = {Isa::Scalar, Isa::Avx2, Isa::Avx512};

// Random triangles, and unit squares facing each axis on a lattice (bvh_checks.h).
test::Soup kernelScene() {
    test::Soup soup = test::randomSoup(2000, 31, 6.0f, 1.0f);
    test::addLatticeSquares(soup, 3, 3);
    return soup;
}

std::vector<Ray> kernelRays() {
    std::vector<Ray> rays;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> pos(-8.0f, 8.0f), dir(-1.0f, 1.0f);
    for (int i = 0; i < 3000; ++i) {  // random, a fifth with an interval reaching below 0
        Ray ray;
        ray.org = Vec3(pos(rng), pos(rng), pos(rng));
        ray.dir = Vec3(dir(rng), dir(rng), dir(rng));
        if (i % 5 == 0) ray.tmin = -4.0f;
        rays.push_back(ray);
    }
    for (const Ray& ray : test::axisRaysThroughLattice(3)) rays.push_back(ray);
    for (int i = 0; i < 500; ++i) {  // grazing: in the plane of a lattice square, across its edges
        const int axis = i % 3, u = (axis + 1) % 3, v = (axis + 2) % 3;
        Ray ray;
        ray.org[axis] = float(i % 4);
        ray.org[u] = -1.0f, ray.org[v] = float(i % 7) * 0.5f;
        ray.dir[axis] = 0.0f, ray.dir[u] = 1.0f, ray.dir[v] = dir(rng) * 0.1f;
        rays.push_back(ray);
    }
    return rays;
}

// The wide layouts' packets (plain and coherent) are of 16 rays in the avx512 kernels and of 8
// in the others (packet_traversal.h): a ray's work in a batch depends on its packet, its answer
// does not. Streams (stream_traversal.h) are of 64 rays in every kernel.
bool sameGroups(BatchTraversal path, Isa a, Isa b) {
    return path == BatchTraversal::Stream || (a == Isa::Avx512) == (b == Isa::Avx512);
}

void expectSameCounters(const QueryCounters& a, const QueryCounters& b, const std::string& what) {
    EXPECT_EQ(a.queries, b.queries) << what;
    EXPECT_EQ(a.traversalSteps, b.traversalSteps) << what;
    EXPECT_EQ(a.intersectionTests, b.intersectionTests) << what;
}

void expectSameHit(const Hit& a, const Hit& b, const std::string& what) {
    EXPECT_EQ(std::bit_cast<uint32_t>(a.t), std::bit_cast<uint32_t>(b.t)) << what;
    EXPECT_EQ(a.primitive, b.primitive) << what;
    EXPECT_EQ(std::bit_cast<uint32_t>(a.u), std::bit_cast<uint32_t>(b.u)) << what;
    EXPECT_EQ(std::bit_cast<uint32_t>(a.v), std::bit_cast<uint32_t>(b.v)) << what;
}

// What one kernel answers on the rays: single and batch queries, with their counters.
struct Answers {
    std::vector<Hit> hits, batchHits;
    std::vector<uint8_t> occluded, batchOccluded;
    std::vector<RayCost> costs;
    QueryCounters single, batch;
};

// The form that counts nothing (QueryCounters::counting = false, what timed queries run)
// answers as the counting one bit for bit, single and batch, and counts only the queries.
void expectTimedFormAnswersAlike(const Accelerator& accel, const std::vector<Ray>& rays, const Answers& counted) {
    QueryCounters timed;
    timed.counting = false;
    std::vector<Hit> batchHits(rays.size());
    std::vector<uint8_t> batchOccluded(rays.size());
    accel.findNearestBatch(rays, batchHits, timed, {}, RayCoherence::Coherent);
    accel.isOccludedBatch(rays, batchOccluded, timed, {}, RayCoherence::Coherent);
    for (size_t i = 0; i < rays.size(); ++i) {
        Hit hit;
        accel.findNearest(rays[i], hit, timed);
        expectSameHit(hit, counted.hits[i], "timed ray " + std::to_string(i));
        EXPECT_EQ(accel.isOccluded(rays[i], timed), bool(counted.occluded[i])) << "timed ray " << i;
        expectSameHit(batchHits[i], counted.batchHits[i], "timed batch ray " + std::to_string(i));
        EXPECT_EQ(batchOccluded[i], counted.batchOccluded[i]) << "timed batch ray " << i;
    }
    EXPECT_EQ(timed.queries, 4 * rays.size());
    EXPECT_EQ(timed.traversalSteps, 0u);
    EXPECT_EQ(timed.intersectionTests, 0u);
}

template <typename Layout>
Answers answersOf(const TraversalConfig& config, const test::Soup& soup, const std::vector<Ray>& rays) {
    BvhAccelerator<Layout> accel(builderRecord("sahbvh"), BvhBuildConfig{}, config);
    accel.build(soup.prims());
    Answers a;
    a.hits.resize(rays.size());
    a.occluded.resize(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
        accel.findNearest(rays[i], a.hits[i], a.single);
        a.occluded[i] = accel.isOccluded(rays[i], a.single);
    }
    a.batchHits.resize(rays.size());
    a.batchOccluded.resize(rays.size());
    a.costs.resize(rays.size());
    accel.findNearestBatch(rays, a.batchHits, a.batch, a.costs, RayCoherence::Coherent);
    accel.isOccludedBatch(rays, a.batchOccluded, a.batch, {}, RayCoherence::Coherent);
    expectTimedFormAnswersAlike(accel, rays, a);
    const BuildStats stats = accel.buildStats();
    const auto bits = std::find_if(stats.figures.begin(), stats.figures.end(),
                                   [](const NamedFigure& f) { return f.name == "kernel_bits"; });
    EXPECT_TRUE(bits != stats.figures.end() && bits->value == isaVectorBits(config.isa)) << isaName(config.isa);
    return a;
}

// `a` answers as `reference`, hit for hit and bit for bit; with the same work per ray and in
// total where both traced the same packets (`sameBatchWork`).
void expectSameAnswers(const Answers& a, const Answers& reference, const std::string& what, bool sameBatchWork) {
    for (size_t i = 0; i < a.hits.size(); ++i) {
        expectSameHit(a.hits[i], reference.hits[i], what + " ray " + std::to_string(i));
        expectSameHit(a.batchHits[i], reference.batchHits[i], what + " batch ray " + std::to_string(i));
        EXPECT_EQ(a.occluded[i], reference.occluded[i]) << what << " ray " << i;
        EXPECT_EQ(a.batchOccluded[i], reference.batchOccluded[i]) << what << " batch ray " << i;
        if (!sameBatchWork) continue;
        EXPECT_EQ(a.costs[i].intersectionTests, reference.costs[i].intersectionTests) << what << " ray " << i;
        EXPECT_EQ(a.costs[i].traversalSteps, reference.costs[i].traversalSteps) << what << " ray " << i;
    }
    expectSameCounters(a.single, reference.single, what);
    if (sameBatchWork)
        expectSameCounters(a.batch, reference.batch, what + " batch");
    else
        EXPECT_EQ(a.batch.queries, reference.batch.queries) << what;
}

template <typename Layout>
void expectKernelsAgree(const char* layout) {
    const test::Soup soup = kernelScene();
    const std::vector<Ray> rays = kernelRays();
    for (bool robust : {true, false})
        for (BatchTraversal path : {BatchTraversal::Packets, BatchTraversal::Coherent, BatchTraversal::Stream}) {
            const Answers reference =
                answersOf<Layout>({.robust = robust, .isa = Isa::Scalar, .batchTraversal = path}, soup, rays);
            size_t found = 0;
            for (const Hit& h : reference.hits) found += h.primitive != kInvalidPrimitive;
            EXPECT_GT(found, rays.size() / 4);
            EXPECT_LT(found, rays.size());
            for (Isa isa : kIsas) {
                if (isa == Isa::Scalar || !cpuRuns(isa)) continue;
                std::printf("[ kernels  ] %s robust=%d %s: %s against scalar\n", layout, int(robust),
                            batchTraversalName(path), isaName(isa));
                const Answers a = answersOf<Layout>({.robust = robust, .isa = isa, .batchTraversal = path}, soup, rays);
                const std::string what = std::string(layout) + " " + isaName(isa) + (robust ? "" : " not robust") +
                                         " " + batchTraversalName(path);
                expectSameAnswers(a, reference, what, sameGroups(path, isa, Isa::Scalar));
            }
        }
}

// BVH::singleStep=octant (the single-ray loop compiled per direction octant) against offsets,
// in every kernel this CPU runs, robust or not: the same answers and the same work, ray by ray.
// Batches go ray by ray too (BVH::batchTraversal=single), so that they take the step as well.
template <typename Layout>
void expectSingleStepsAgree(const char* layout) {
    const test::Soup soup = kernelScene();
    const std::vector<Ray> rays = kernelRays();
    for (bool robust : {true, false}) {
        for (Isa isa : kIsas) {
            if (!cpuRuns(isa)) continue;
            TraversalConfig config{.robust = robust, .isa = isa, .batchTraversal = BatchTraversal::Single};
            const Answers offsets = answersOf<Layout>(config, soup, rays);
            config.singleStep = SingleStep::Octant;
            const Answers octant = answersOf<Layout>(config, soup, rays);
            expectSameAnswers(octant, offsets,
                              std::string(layout) + " " + isaName(isa) + (robust ? "" : " not robust") + " octant step",
                              true);
        }
    }
}

TEST(TraversalKernels, EveryKernelTheCpuRunsAnswersAsTheScalarOne) {
    expectKernelsAgree<BinaryBvh>("binary");
    expectKernelsAgree<WideBvh<4>>("wide4");
    expectKernelsAgree<WideBvh<8>>("wide8");
}

TEST(TraversalKernels, OctantStepAnswersAsOffsetsStep) {
    Env env(verify::verifyKeys());
    EXPECT_EQ(bvhSettingsFromEnv(env).traversal.singleStep, SingleStep::Offsets);
    env.set(keys::BVH::singleStep, "octant", "test");
    EXPECT_EQ(bvhSettingsFromEnv(env).traversal.singleStep, SingleStep::Octant);
    expectSingleStepsAgree<WideBvh<4>>("wide4");
    expectSingleStepsAgree<WideBvh<8>>("wide8");
}

TEST(TraversalKernels, AutoIsTheBestTheCpuRuns) {
    const Isa best = bestIsa();
    EXPECT_NE(best, Isa::Auto);
    EXPECT_TRUE(cpuRuns(best));
    EXPECT_EQ(traversalKernels<WideBvh<8>>(TraversalConfig{}).isa, best);
    std::printf("[ kernels  ] this CPU runs up to %s\n", isaName(best));
    if (best == Isa::Avx512) {
        EXPECT_TRUE(cpuRuns(Isa::Avx2));
    }
}

TEST(TraversalKernels, BvhIsaPicksTheKernelsOrSaysWhatTheCpuLacks) {
    for (Isa isa : kIsas) {
        Env env(verify::verifyKeys());
        env.set(keys::BVH::isa, isaName(isa), "test");
        EXPECT_EQ(bvhSettingsFromEnv(env).traversal.isa, isa);
        if (cpuRuns(isa)) {
            EXPECT_NO_THROW((void)createAccelerator("sahbvh8", env)) << isaName(isa);
            continue;
        }
        try {
            (void)createAccelerator("sahbvh8", env);
            ADD_FAILURE() << "no error for BVH::isa=" << isaName(isa);
        } catch (const InputError& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(std::string("BVH::isa=") + isaName(isa)), std::string::npos) << message;
            EXPECT_NE(message.find(isaName(bestIsa())), std::string::npos) << message;
        }
    }
    Env env(verify::verifyKeys());
    EXPECT_THROW(env.set(keys::BVH::isa, "sse9", "test"), InputError);
    EXPECT_EQ(bvhSettingsFromEnv(env).traversal.isa, Isa::Auto);
}

}  // namespace
}  // namespace bvhlab
