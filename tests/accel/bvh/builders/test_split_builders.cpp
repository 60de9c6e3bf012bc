// The split builders (tdbvh, sahbvh, sweepbvh, ploc) on random and adversarial scenes: every
// tree invariant, tiny and degenerate inputs, coincident and collinear centres, the depth bound,
// sizes over nine decades, and the recursion's refusal of a split that leaves a half empty.
#include "accel/bvh/builders/split_rule.h"
#include "accel/bvh/bvh_accelerator.h"
#include "framework/core/timed_build.h"
#include "tests/support/bvh_checks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace bvhlab {
namespace {

using test::allBuilders;
using test::buildAndCheck;
using test::checkTree;
using test::expectAgreesWithNaive;
using test::mixedScaleSoup;
using test::randomSoup;
using test::Soup;
using test::TreeFacts;

TEST(Bvh, InvariantsOnRandomScenes) {
    const Soup soup = randomSoup(3000, 1);
    for (const BuilderRecord& kind : allBuilders()) {
        for (bool simd : {true, false}) {
            SCOPED_TRACE(kind.name + (simd ? " simd" : " scalar"));
            BvhBuildConfig config;
            config.shared.simd = simd;
            BvhAccelerator<BinaryBvh> accel(kind, config);
            buildAndCheck(accel, soup);
        }
    }
    // The other settings of each builder.
    BvhBuildConfig allAxes;
    allAxes.binnedSah.allAxes = true;
    allAxes.binnedSah.bins = 7;
    BvhBuildConfig nodeBox;
    nodeBox.spatialMedian.splitBox = MedianSplitBox::NodeBox;
    BvhBuildConfig manyBins;
    manyBins.binnedSah.bins = 256;
    for (const auto& [kind, config] :
         {std::pair{builderRecord("sahbvh"), allAxes}, std::pair{builderRecord("tdbvh"), nodeBox},
          std::pair{builderRecord("sahbvh"), manyBins}}) {
        BvhAccelerator<BinaryBvh> accel(kind, config);
        buildAndCheck(accel, soup);
    }
}

TEST(Bvh, TinyScenes) {
    for (size_t n : {0, 1, 2, 3}) {
        const Soup soup = randomSoup(n, 7 + uint32_t(n));
        for (const BuilderRecord& kind : allBuilders()) {
            SCOPED_TRACE(kind.name + " with " + std::to_string(n) + " triangles");
            BvhBuildConfig config;
            config.shared.maxLeaf = 1;
            config.shared.sahTermination = false;
            BvhAccelerator<BinaryBvh> accel(kind, config);
            const TreeFacts facts = buildAndCheck(accel, soup);
            EXPECT_EQ(facts.leaves, n);
            // A ray at each triangle's centroid finds it (or one equally near).
            for (uint32_t prim : soup.valid) {
                const Triangle& t = soup.triangles[prim];
                Ray ray;
                ray.org = t.centroid() + 5.0f * glm::normalize(t.geometricNormal());
                ray.dir = t.centroid() - ray.org;
                Hit hit;
                QueryCounters counters;
                ASSERT_TRUE(accel.findNearest(ray, hit, counters));
                EXPECT_LE(hit.t, 1.0001f);
                EXPECT_TRUE(accel.isOccluded(ray, counters));
                EXPECT_EQ(counters.queries, 2u);
                EXPECT_GE(counters.traversalSteps, 2u);
            }
            // Nothing to hit.
            Ray away;
            away.org = {-100, -100, -100};
            away.dir = {-1, 0, 0};
            Hit hit;
            QueryCounters counters;
            EXPECT_FALSE(accel.findNearest(away, hit, counters));
            EXPECT_FALSE(hit.found());
            EXPECT_FALSE(accel.isOccluded(away, counters));
        }
    }
}

TEST(Bvh, DegeneratePrimitivesAreNotBuiltOver) {
    // Valid lists only some triangles: the others never appear in leaves; hits report the
    // primitive index of the full list.
    Soup soup = randomSoup(50, 3);
    soup.valid = {4, 9, 10, 31, 49};
    for (const BuilderRecord& kind : allBuilders()) {
        BvhAccelerator<BinaryBvh> accel(kind, BvhBuildConfig{});
        buildAndCheck(accel, soup);
        expectAgreesWithNaive(accel, soup, 300, 10.0f, 5);
    }
}

// A BVH promises its bounds through BuildStats (what `bvhlab stress` holds it to): a depth
// below kBvhMaxDepth and leaves of at most max(maxLeaf, leafCap) primitives, and keeps them,
// here on coincident triangles, where no split separates anything.
TEST(Bvh, ReportsTheBoundsItPromisesAndKeepsThem) {
    Soup soup = randomSoup(10, 3);
    for (int i = 0; i < 3000; ++i) soup.add(soup.triangles[0]);
    BvhBuildConfig config = BvhBuildConfig{};
    config.shared.leafCap = 5;
    for (const BuilderRecord& kind : allBuilders()) {
        BvhAccelerator<BinaryBvh> accel(kind, config);
        buildAndCheck(accel, soup);
        const BuildStats stats = timedBuild(accel, soup.prims());
        ASSERT_TRUE(stats.leafBound && stats.depthBound);
        EXPECT_EQ(*stats.leafBound, 5u);
        EXPECT_EQ(*stats.depthBound, kBvhMaxDepth);
        EXPECT_LE(*stats.maxLeafPrimitives, *stats.leafBound);
        EXPECT_LT(*stats.maxDepth, *stats.depthBound);
    }
}

TEST(Bvh, HundredThousandCoincidentTriangles) {
    Soup soup;
    for (int i = 0; i < 100000; ++i) soup.add({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    for (const BuilderRecord& kind : allBuilders()) {
        SCOPED_TRACE(kind.name);
        BvhAccelerator<BinaryBvh> accel(kind, BvhBuildConfig{});
        const BuildStats stats = timedBuild(accel, soup.prims());
        EXPECT_LT(stats.buildMs, 2000.0);
        const TreeFacts facts = checkTree(accel.bvh(), soup);
        // Split by index into halves: depth log2(100000 / leafCap) + 1.
        EXPECT_LE(facts.maxDepth, 14);
        EXPECT_LE(facts.maxLeaf, size_t(BvhBuildConfig{}.shared.leafCap));

        Ray ray;
        ray.org = {0.25f, 0.25f, 1.0f};
        ray.dir = {0, 0, -1};
        Hit hit;
        QueryCounters counters;
        ASSERT_TRUE(accel.findNearest(ray, hit, counters));
        EXPECT_FLOAT_EQ(hit.t, 1.0f);
    }
    // With leafCap 1 every leaf holds one primitive even here.
    BvhBuildConfig strict;
    strict.shared.maxLeaf = 1;
    strict.shared.leafCap = 1;
    strict.shared.sahTermination = false;
    BvhAccelerator<BinaryBvh> accel(builderRecord("sahbvh"), strict);
    accel.build(soup.prims());
    EXPECT_EQ(checkTree(accel.bvh(), soup).maxLeaf, 1u);
}

TEST(Bvh, CentresOnALineOnAPlaneAndClustered) {
    Soup line, plane, clusters;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 100.0f);
    for (int i = 0; i < 4000; ++i) {
        const float x = u(rng), y = u(rng);
        line.add({{x - 1, -1, 0}, {x + 1, -1, 0}, {x, 2, 0}});             // centres on the x axis
        plane.add({{x - 1, y - 1, 0}, {x + 1, y - 1, 0}, {x, y + 2, 0}});  // centres in z = 0
        const float c = float(i % 8) * 10.0f;                              // 8 points, 500 each
        clusters.add({{c - 1, -1, 0}, {c + 1, -1, 0}, {c, 2, 0}});
    }
    for (const Soup* soup : {&line, &plane, &clusters}) {
        for (const BuilderRecord& kind : allBuilders()) {
            for (MedianSplitBox box : {MedianSplitBox::CentroidBox, MedianSplitBox::NodeBox}) {
                if (kind.name != "tdbvh" && box == MedianSplitBox::NodeBox) continue;
                BvhBuildConfig config;
                config.spatialMedian.splitBox = box;
                BvhAccelerator<BinaryBvh> accel(kind, config);
                buildAndCheck(accel, *soup);
                expectAgreesWithNaive(accel, *soup, 200, 100.0f, 13);
            }
        }
    }
}

TEST(Bvh, DepthStaysBoundedOnGeometricSpacing) {
    // Centres at x = 1.5^i: the middle of the centre box separates only the last one, so a
    // spatial median would build a chain of depth N; the builders must stop short of 64.
    Soup soup;
    for (int i = 0; i < 200; ++i) {
        const float x = std::pow(1.5f, float(i) - 100.0f);
        soup.add({{x, 0, 0}, {x * 1.01f, 0, 0}, {x, 1e-3f, 1e-3f}});
    }
    for (const BuilderRecord& kind : allBuilders()) {
        for (MedianSplitBox box : {MedianSplitBox::CentroidBox, MedianSplitBox::NodeBox}) {
            SCOPED_TRACE(kind.name);
            BvhBuildConfig config;
            config.shared.maxLeaf = 1;
            config.shared.sahTermination = false;
            config.spatialMedian.splitBox = box;
            BvhAccelerator<BinaryBvh> accel(kind, config);
            const TreeFacts facts = buildAndCheck(accel, soup);
            EXPECT_EQ(facts.leaves, soup.valid.size());
            EXPECT_LT(facts.maxDepth, kBvhMaxDepth);
            if (kind.name == "tdbvh" && box == MedianSplitBox::CentroidBox) {
                EXPECT_GE(facts.maxDepth, 40) << "the chain this test is about did not occur";
            }
        }
    }
}

TEST(Bvh, SizesFromMicrometresToKilometres) {
    const Soup soup = mixedScaleSoup(3000, 17);
    for (const BuilderRecord& kind : allBuilders()) {
        BvhAccelerator<BinaryBvh> accel(kind, BvhBuildConfig{});
        buildAndCheck(accel, soup);
        expectAgreesWithNaive(accel, soup, 1000, 1000.0f, 19);
    }
}

// A split rule that breaks the hook's contract: it hands back an empty left half.
class EmptyHalfSplitRule : public BvhSplitRule {
public:
    using BvhSplitRule::BvhSplitRule;

protected:
    std::optional<Split> trySplit(const BuildRange& range, bool) override {
        return Split{{range.begin, range.begin, {}, {}}, range};
    }
};

// An empty half would become a node of count 0, which reads as an inner node: the recursion
// refuses it instead of building a tree that traverses garbage.
TEST(Bvh, RecursionRefusesASplitWithAnEmptyHalf) {
    std::vector<PrimRef> refs(8);
    BuildRange root{0, 8, {}, {}};
    for (uint32_t i = 0; i < 8; ++i) {
        refs[i] = {{float(i), 0.0f, 0.0f}, i, {float(i) + 0.5f, 1.0f, 1.0f}, 0};
        root.bounds.extend(Bounds3{{float(i), 0.0f, 0.0f}, {float(i) + 0.5f, 1.0f, 1.0f}});
        root.centroidBounds.extend(Vec3(float(i) + 0.25f, 0.5f, 0.5f));
    }
    BuildConfig config;
    config.maxLeaf = 1;
    EmptyHalfSplitRule builder(config);
    EXPECT_THROW(builder.build(refs, root), std::logic_error);
}

}  // namespace
}  // namespace bvhlab
