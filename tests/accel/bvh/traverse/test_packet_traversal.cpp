// Batches traced as packets (packet_traversal.h), plain and coherent (BVH::batchTraversal=
// packets, coherent: coherent_traversal.h), and as streams (stream_traversal.h) against the
// single-ray traversal of the same tree: hits bit for bit (t, u, v, primitive) and occluded
// flags equal, on ray sets chosen to take every path (coherent packets, packets thinning out to
// single rays, incoherent streams, rays left alone: tmin < 0, NaN), and on coplanar duplicate
// triangles, whose ties the closest hit must break the same way whatever the visit order
// (ClosestHitQuery::record). The counts of a packet or a stream differ from single-ray counts
// by design; only the queries must match, and each ray's costs must add up to the totals.
#include "accel/bvh/builder_table.h"
#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/bvh_env.h"
#include "accel/bvh/traverse/packet_traversal.h"
#include "accel/bvh/traverse/stream_traversal.h"
#include "accel/verify/verify_keys.h"
#include "tests/support/triangle_soup.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <random>

namespace bvhlab {
namespace {

using test::Soup;

// Triangles of sizes 0.05 to 1 in a 20-unit cube over a floor of 2 x 2-unit quads at y = -10.
Soup randomScene(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-10.0f, 10.0f), unit(-1.0f, 1.0f), size(0.05f, 1.0f);
    Soup soup;
    for (int i = 0; i < 3000; ++i) {
        const Vec3 p(pos(rng), pos(rng), pos(rng));
        const float s = size(rng);
        soup.add({p, p + s * Vec3(unit(rng), unit(rng), unit(rng)), p + s * Vec3(unit(rng), unit(rng), unit(rng))});
    }
    for (int x = -10; x < 10; x += 2)
        for (int z = -10; z < 10; z += 2) {
            const Vec3 a(float(x), -10.0f, float(z)), b(float(x + 2), -10.0f, float(z)),
                c(float(x + 2), -10.0f, float(z + 2)), d(float(x), -10.0f, float(z + 2));
            soup.add({a, b, c});
            soup.add({a, c, d});
        }
    return soup;
}

// Every triangle four times over (in different leaves as the builder cuts them): an
// axis-aligned floor of 1-unit quads and a slanted wall of the same quads, so that most hits
// are ties of equal t.
Soup duplicatesScene() {
    Soup soup;
    const auto quad = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
        for (int copy = 0; copy < 4; ++copy) soup.add({a, b, c}), soup.add({a, c, d});
    };
    for (int x = -8; x < 8; ++x)
        for (int z = -8; z < 8; ++z) {
            quad(Vec3(float(x), 0.0f, float(z)), Vec3(float(x + 1), 0.0f, float(z)),
                 Vec3(float(x + 1), 0.0f, float(z + 1)), Vec3(float(x), 0.0f, float(z + 1)));
            quad(Vec3(float(x), 0.3f * float(z), -4.0f - float(z)),
                 Vec3(float(x + 1), 0.3f * float(z), -4.0f - float(z)),
                 Vec3(float(x + 1), 0.3f * float(z + 1), -5.0f - float(z)),
                 Vec3(float(x), 0.3f * float(z + 1), -5.0f - float(z)));
        }
    return soup;
}

// Camera rays through a grid from `eye` towards the origin, in rows (consecutive rays are
// neighbours), with a ray of tmin < 0 every 29th and a NaN ray every 31st mixed in.
std::vector<Ray> primaryRays(Vec3 eye, int width, int height) {
    std::vector<Ray> rays;
    const Vec3 forward = glm::normalize(-eye), right = glm::normalize(glm::cross(forward, Vec3(0, 1, 0))),
               up = glm::cross(right, forward);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float u = (float(x) + 0.5f) / float(width) * 2.0f - 1.0f,
                        v = (float(y) + 0.5f) / float(height) * 2.0f - 1.0f;
            Ray r{eye, forward + 0.8f * u * right + 0.8f * v * up};
            const size_t i = rays.size();
            if (i % 29 == 0) r.tmin = -5.0f;
            if (i % 31 == 0) r.dir.x = std::numeric_limits<float>::quiet_NaN();
            rays.push_back(r);
        }
    return rays;
}

// Rays in random directions from random origins.
std::vector<Ray> incoherentRays(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-14.0f, 14.0f);
    std::vector<Ray> rays;
    for (size_t i = 0; i < n; ++i) {
        const Vec3 org(pos(rng), pos(rng), pos(rng));
        rays.push_back({org, Vec3(pos(rng), pos(rng), pos(rng)) - org});
    }
    return rays;
}

// Axis-parallel rays (both signs, -0 included) from origins on the unit grid, which lie on
// box planes (NaN slab distances), and grazing rays in the floors' planes.
std::vector<Ray> axisAndGrazingRays(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> cell(-12, 12);
    std::uniform_real_distribution<float> angle(0.0f, 6.2831853f);
    std::vector<Ray> rays;
    for (int i = 0; i < 1500; ++i) {
        Vec3 dir(0.0f);
        dir[i % 3] = i % 2 ? 1.0f : -1.0f;
        if (i % 10 == 0) dir[(i + 1) % 3] = -0.0f;
        rays.push_back({Vec3(float(cell(rng)), float(cell(rng)), float(cell(rng))), dir});
    }
    for (int i = 0; i < 1500; ++i) {
        const float a = angle(rng), y = i % 2 ? 0.0f : -10.0f;
        rays.push_back({Vec3(float(cell(rng)), y, float(cell(rng))), Vec3(std::cos(a), 0.0f, std::sin(a))});
    }
    return rays;
}

// Shadow rays from the closest hits of `rays` towards a light, ending at it (tmax = 1 along
// the unnormalised direction), starting just off the surface.
std::vector<Ray> shadowRays(const Accelerator& accel, const std::vector<Ray>& rays, Vec3 light) {
    std::vector<Ray> shadows;
    QueryCounters counters;
    for (const Ray& r : rays) {
        Hit hit;
        if (!accel.findNearest(r, hit, counters)) continue;
        const Vec3 p = r.org + hit.t * r.dir;
        Ray s{p, light - p};
        s.tmin = 1e-4f;
        s.tmax = 1.0f;
        shadows.push_back(s);
    }
    return shadows;
}

bool bitEqual(const Hit& a, const Hit& b) { return std::memcmp(&a, &b, sizeof(Hit)) == 0; }

// What a ray set must match bit for bit: everything, or t alone where the hits are ties
// between leaves whose box the hit point bounds (rays through an edge shared by two leaves'
// triangles): the box test's entry there may round above the hit's t, so the leaf visited
// second is culled and the tie rule never sees it. Which triangle is reported then depends on
// the visit order (docs/architecture.md, Packets). Without robustness (BVH::robust=false:
// Moeller-Trumbore, no far margin) the same happens to near ties, hits within rounding of
// each other: t then agrees within the oracle's tolerance (hitsAgree), not bit for bit.
enum class Match { Bits, TiesAtLeafBoundaries, NearTiesAtLeafBoundaries };

// The batch calls against the single-ray calls on `rays`; `hitsExpected`: at least a tenth
// of the rays hit (occluded, for shadow rays).
void expectBatchAsSingle(const Accelerator& accel, const std::vector<Ray>& rays, const std::string& what,
                         Match match = Match::Bits) {
    SCOPED_TRACE(what);
    QueryCounters single, singleOcc, batch, batchOcc;
    std::vector<Hit> expected(rays.size());
    std::vector<uint8_t> expectedOcc(rays.size());
    size_t hitCount = 0, occludedCount = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        hitCount += accel.findNearest(rays[i], expected[i], single);
        expectedOcc[i] = accel.isOccluded(rays[i], singleOcc);
        occludedCount += expectedOcc[i];
    }
    std::vector<Hit> hits(rays.size(), Hit{1.0f, 5, 0.5f, 0.5f});
    std::vector<uint8_t> occluded(rays.size(), 2);
    std::vector<RayCost> costs(rays.size()), occCosts(rays.size());
    accel.findNearestBatch(rays, hits, batch, costs, RayCoherence::Coherent);
    accel.isOccludedBatch(rays, occluded, batchOcc, occCosts, RayCoherence::Coherent);
    EXPECT_GT(std::max(hitCount, occludedCount), rays.size() / 20);  // the set tests something
    size_t failures = 0, ties = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        if (bitEqual(hits[i], expected[i]) && occluded[i] == expectedOcc[i]) continue;
        const bool tie = match == Match::TiesAtLeafBoundaries
                             ? std::memcmp(&hits[i].t, &expected[i].t, sizeof(float)) == 0
                             : match == Match::NearTiesAtLeafBoundaries && hitsAgree(hits[i], expected[i]);
        if (tie && occluded[i] == expectedOcc[i]) {
            ++ties;
            continue;
        }
        if (++failures > 5) continue;
        ADD_FAILURE() << "ray " << i << ": batch t " << hits[i].t << " prim " << hits[i].primitive << " occluded "
                      << int(occluded[i]) << "; single t " << expected[i].t << " prim " << expected[i].primitive
                      << " occluded " << int(expectedOcc[i]);
    }
    EXPECT_LE(ties, rays.size() / 100);
    EXPECT_EQ(batch.queries, single.queries);
    EXPECT_EQ(batchOcc.queries, singleOcc.queries);
    for (const auto& [list, total] : {std::pair{&costs, &batch}, std::pair{&occCosts, &batchOcc}}) {
        uint64_t tests = 0, steps = 0;
        for (const RayCost& c : *list) tests += c.intersectionTests, steps += c.traversalSteps;
        EXPECT_EQ(tests, total->intersectionTests);
        EXPECT_EQ(steps, total->traversalSteps);
    }
}

// Every ray set through `accel`'s batches against its single rays.
void expectRaySetsAsSingle(const Accelerator& accel, bool robust, Match axisParallel) {
    const std::vector<Ray> primary = primaryRays(Vec3(3, 14, 22), 64, 48);
    expectBatchAsSingle(accel, primary, "primary");
    // Low and behind the wall of duplicatesScene, so that many shadow rays are occluded.
    expectBatchAsSingle(accel, shadowRays(accel, primary, Vec3(2, 1.5f, -25)), "shadow");
    expectBatchAsSingle(accel, incoherentRays(4000, 3), "incoherent");
    const Match boundary = robust || axisParallel == Match::Bits ? axisParallel : Match::NearTiesAtLeafBoundaries;
    expectBatchAsSingle(accel, axisAndGrazingRays(5), "axis-parallel and grazing", boundary);
}

// Every ray set on `soup`, for a layout, through the batch path `traversal` sets, robust and not.
template <typename Layout>
void expectTraversalAsSingle(const Soup& soup, Match axisParallel, TraversalConfig traversal) {
    for (const bool robust : {true, false}) {
        SCOPED_TRACE(std::string(batchTraversalName(traversal.batchTraversal)) + ", robust " + std::to_string(robust));
        traversal.robust = robust;
        BvhAccelerator<Layout> accel(builderRecord("sahbvh"), BvhBuildConfig{}, traversal);
        accel.build(soup.prims());
        expectRaySetsAsSingle(accel, robust, axisParallel);
    }
}

// The same on the packet path `path` at each fallback threshold (0: packets to the leaves;
// 2: the default; 64: every ray alone from the root).
template <typename Layout>
void expectPacketsAsSingle(const Soup& soup, Match axisParallel = Match::Bits,
                           BatchTraversal path = BatchTraversal::Packets) {
    for (const int fallback : {0, 2, 64}) {
        SCOPED_TRACE("fallback " + std::to_string(fallback));
        TraversalConfig traversal;
        traversal.packetFallback = fallback;
        traversal.batchTraversal = path;
        expectTraversalAsSingle<Layout>(soup, axisParallel, traversal);
    }
}

TEST(PacketTraversal, Wide8AnswersAsSingleRays) { expectPacketsAsSingle<WideBvh<8>>(randomScene(1)); }
TEST(PacketTraversal, Wide4AnswersAsSingleRays) { expectPacketsAsSingle<WideBvh<4>>(randomScene(2)); }
// Duplicates tie everywhere: bit for bit, but for the axis-parallel rays from the unit grid,
// which pass exactly through edges shared by the quads of the wall (Match above).
TEST(PacketTraversal, TiesOnDuplicatesAnswerAsSingleRays) {
    expectPacketsAsSingle<WideBvh<8>>(duplicatesScene(), Match::TiesAtLeafBoundaries);
    expectPacketsAsSingle<WideBvh<4>>(duplicatesScene(), Match::TiesAtLeafBoundaries);
}

// The coherent packets: the frustum before the rays' box tests, one triangle against all rays
// at leaves.
TEST(CoherentTraversal, Wide8AnswersAsSingleRays) {
    expectPacketsAsSingle<WideBvh<8>>(randomScene(1), Match::Bits, BatchTraversal::Coherent);
}
TEST(CoherentTraversal, Wide4AnswersAsSingleRays) {
    expectPacketsAsSingle<WideBvh<4>>(randomScene(2), Match::Bits, BatchTraversal::Coherent);
}
TEST(CoherentTraversal, TiesOnDuplicatesAnswerAsSingleRays) {
    expectPacketsAsSingle<WideBvh<8>>(duplicatesScene(), Match::TiesAtLeafBoundaries, BatchTraversal::Coherent);
    expectPacketsAsSingle<WideBvh<4>>(duplicatesScene(), Match::TiesAtLeafBoundaries, BatchTraversal::Coherent);
}

// The coherent packets walk as the plain ones (the frustum drops no child that a ray hits, the
// packet's leaf test finds each ray's hits), so each ray counts the same work in both.
template <typename Layout>
void expectCoherentCountsAsPackets(const Soup& soup) {
    for (const bool robust : {true, false}) {
        SCOPED_TRACE("robust " + std::to_string(robust));
        std::vector<Ray> rays = primaryRays(Vec3(3, 14, 22), 64, 48);
        const std::vector<Ray> incoherent = incoherentRays(2000, 7);
        rays.insert(rays.end(), incoherent.begin(), incoherent.end());
        std::vector<RayCost> costs[2][2];  // [path][closest, any]
        for (const BatchTraversal path : {BatchTraversal::Packets, BatchTraversal::Coherent}) {
            const int p = path == BatchTraversal::Coherent ? 1 : 0;
            BvhAccelerator<Layout> accel(builderRecord("sahbvh"), BvhBuildConfig{},
                                         TraversalConfig{.robust = robust, .batchTraversal = path});
            accel.build(soup.prims());
            std::vector<Hit> hits(rays.size());
            std::vector<uint8_t> occluded(rays.size());
            QueryCounters counters;
            costs[p][0].resize(rays.size()), costs[p][1].resize(rays.size());
            accel.findNearestBatch(rays, hits, counters, costs[p][0], RayCoherence::Coherent);
            accel.isOccludedBatch(rays, occluded, counters, costs[p][1], RayCoherence::Coherent);
        }
        for (int query = 0; query < 2; ++query) {
            size_t differing = 0;
            for (size_t i = 0; i < rays.size(); ++i)
                differing += costs[1][query][i].intersectionTests != costs[0][query][i].intersectionTests ||
                             costs[1][query][i].traversalSteps != costs[0][query][i].traversalSteps;
            EXPECT_EQ(differing, 0u) << (query == 0 ? "closest hit" : "any hit");
        }
    }
}
TEST(CoherentTraversal, CountsAsPlainPackets) {
    expectCoherentCountsAsPackets<WideBvh<8>>(randomScene(4));
    expectCoherentCountsAsPackets<WideBvh<4>>(duplicatesScene());
}

// The binary layout keeps its single loop, and the tie rule is the same there: of four
// duplicates the first in leaf order, whichever leaf is visited first.
TEST(PacketTraversal, BinaryBatchAnswersAsSingleRays) { expectPacketsAsSingle<BinaryBvh>(duplicatesScene()); }

// Packets of 16 (AVX-512's width; here whatever backend Floats<16> is, Scalar<16> on AVX2
// machines) answer as single rays too: tracePacket for every width the batch entry may pick.
template <PacketKind Kind>
void expectSixteenRayPacketsAsSingle() {
    BvhAccelerator<WideBvh<8>> accel(builderRecord("sahbvh"), BvhBuildConfig{});
    accel.build(randomScene(3).prims());
    const WideBvh<8>& tree = accel.bvh();
    std::vector<Ray> rays;
    for (const Ray& r : primaryRays(Vec3(3, 14, 22), 64, 48))
        if (r.isValid() && r.tmin >= 0.0f) rays.push_back(r);
    for (const int fallback : {0, 2, 6}) {
        size_t compared = 0;
        for (size_t begin = 0, count = 0; begin < rays.size(); begin += count) {  // up to 16 of one octant
            const int octant = directionOctant(rays[begin].dir);
            for (count = 1; count < 16 && begin + count < rays.size(); ++count)
                if (directionOctant(rays[begin + count].dir) != octant) break;
            tracePacket<true, ClosestHitQuery, true, 16, Kind>(
                tree, rays.data() + begin, int(count), octant, fallback,
                [&](int k, const ClosestHitQuery& query, const QueryCounters&) {
                    QueryCounters counters;
                    Hit packet, single;
                    answerOf(tree, query, packet);
                    accel.findNearest(rays[begin + k], single, counters);
                    EXPECT_TRUE(bitEqual(packet, single)) << "ray " << begin + k << ", fallback " << fallback;
                    ++compared;
                });
            tracePacket<true, AnyHitQuery, true, 16, Kind>(tree, rays.data() + begin, int(count), octant, fallback,
                                                           [&](int k, const AnyHitQuery& query, const QueryCounters&) {
                                                               QueryCounters counters;
                                                               EXPECT_EQ(query.occluded,
                                                                         accel.isOccluded(rays[begin + k], counters));
                                                           });
        }
        EXPECT_EQ(compared, rays.size());
    }
}
TEST(PacketTraversal, SixteenRayPacketsAnswerAsSingleRays) { expectSixteenRayPacketsAsSingle<PacketKind::Plain>(); }
TEST(CoherentTraversal, SixteenRayPacketsAnswerAsSingleRays) {
    expectSixteenRayPacketsAsSingle<PacketKind::Coherent>();
}

// Every ray set on `soup` through streams, for a layout.
template <typename Layout>
void expectStreamsAsSingle(const Soup& soup, Match axisParallel = Match::Bits) {
    TraversalConfig traversal;
    traversal.batchTraversal = BatchTraversal::Stream;
    expectTraversalAsSingle<Layout>(soup, axisParallel, traversal);
}

TEST(StreamTraversal, Wide8AnswersAsSingleRays) { expectStreamsAsSingle<WideBvh<8>>(randomScene(1)); }
TEST(StreamTraversal, Wide4AnswersAsSingleRays) { expectStreamsAsSingle<WideBvh<4>>(randomScene(2)); }
TEST(StreamTraversal, TiesOnDuplicatesAnswerAsSingleRays) {
    expectStreamsAsSingle<WideBvh<8>>(duplicatesScene(), Match::TiesAtLeafBoundaries);
    expectStreamsAsSingle<WideBvh<4>>(duplicatesScene(), Match::TiesAtLeafBoundaries);
}

// Streams of every length from 1 to kStreamSize, straight through traceStream: the ray masks'
// ends (a full 64-bit mask among them) and each ray's costs against its single-ray answer.
TEST(StreamTraversal, StreamsOfEveryLengthAnswerAsSingleRays) {
    BvhAccelerator<WideBvh<8>> accel(builderRecord("sahbvh"), BvhBuildConfig{});
    accel.build(randomScene(3).prims());
    const WideBvh<8>& tree = accel.bvh();
    std::vector<Ray> rays;  // of octant 0
    for (Ray r : incoherentRays(4000, 9)) {
        r.dir = glm::abs(r.dir);
        rays.push_back(r);
    }
    size_t compared = 0, begin = 0;
    for (int count = 1; count <= kStreamSize; begin += size_t(count), ++count) {
        ASSERT_LE(begin + size_t(count), rays.size());
        const Ray* stream = rays.data() + begin;
        traceStream<true, ClosestHitQuery, true>(
            tree, stream, count, 0, [&](int k, const ClosestHitQuery& query, const QueryCounters& work) {
                QueryCounters counters;
                Hit batch, single;
                answerOf(tree, query, batch);
                accel.findNearest(stream[k], single, counters);
                EXPECT_TRUE(bitEqual(batch, single)) << "stream of " << count << ", ray " << k;
                EXPECT_EQ(work.queries, 1u);
                EXPECT_GE(work.traversalSteps, 1u);  // the root
                ++compared;
            });
        traceStream<false, AnyHitQuery, true>(tree, stream, count, 0,
                                              [&](int k, const AnyHitQuery& query, const QueryCounters& work) {
                                                  QueryCounters counters;
                                                  EXPECT_EQ(query.occluded, accel.isOccluded(stream[k], counters))
                                                      << "stream of " << count << ", ray " << k;
                                                  EXPECT_EQ(work.traversalSteps, 0u);  // the form that counts nothing
                                                  EXPECT_EQ(work.intersectionTests, 0u);
                                              });
    }
    EXPECT_EQ(compared, size_t(kStreamSize) * (kStreamSize + 1) / 2);
}

TEST(StreamTraversal, BatchTraversalKeyNamesStream) {
    Env env(verify::verifyKeys());
    env.set(keys::BVH::batchTraversal, "stream", "test");
    EXPECT_EQ(bvhSettingsFromEnv(env).traversal.batchTraversal, BatchTraversal::Stream);
    EXPECT_STREQ(batchTraversalName(BatchTraversal::Stream), "stream");
}

}  // namespace
}  // namespace bvhlab
