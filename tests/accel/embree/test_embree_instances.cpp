// Embree's instances (accel/embree/embree_instances.h), made by createInstanced with the bottom
// "embree": the world of instances answers as brute force over the same primitives put into the
// world does, before and after the instances move and after one deformed in place (refitted at
// Embree::quality=refit, rebuilt at the others); batches answer as single rays; rays Embree
// cannot take as they are are traced in parts; statistics as EmbreeAccelerator's.
#include "accel/embree/embree_instances.h"
#include "accel/registry.h"
#include "accel/verify/verify_keys.h"
#include "tests/support/instanced_world.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace bvhlab::test {
namespace {

Env envWithQuality(const std::string& quality) {
    Env env(verify::verifyKeys());
    env.setOverride("Embree::quality=" + quality);
    return env;
}

TEST(EmbreeInstances, CreatedForTheBottomEmbreeWithTheEnvsSettings) {
    InstancedWorld scene;
    const std::unique_ptr<InstancedAccelerator> accel = builtAtTimeZero(scene, "embree", envWithQuality("refit"));
    const auto* instances = dynamic_cast<const EmbreeInstances*>(accel.get());
    ASSERT_NE(instances, nullptr);
    EXPECT_EQ(instances->config().quality, EmbreeQuality::Refit);
    EXPECT_EQ(accel->instanceCount(), 3u);
    EXPECT_FALSE(accel->hasCounters());
}

TEST(EmbreeInstances, AnswerAsBruteForceAfterMovesAndADeformationAtEachQuality) {
    for (const char* quality : {"refit", "medium"}) {
        SCOPED_TRACE(quality);
        InstancedWorld scene;
        const std::unique_ptr<InstancedAccelerator> accel = builtAtTimeZero(scene, "embree", envWithQuality(quality));
        expectAnswersAsBruteForce(*accel, scene.world, 7);

        const std::vector<glm::dmat4> moved = placements(1.25);
        scene.place(moved);
        accel->moveInstances(moved, {});
        expectAnswersAsBruteForce(*accel, scene.world, 8);

        // Object 0 is instances 0 and 2: both scenes are brought up to its moved primitives.
        scene.deform(0, 0.5);
        const std::vector<glm::dmat4> again = placements(2.0);
        scene.place(again);
        const uint32_t deformed[] = {0, 2};
        accel->moveInstances(again, deformed);
        expectAnswersAsBruteForce(*accel, scene.world, 9);
    }
}

TEST(EmbreeInstances, BatchesAnswerAsSingleRays) {
    InstancedWorld scene;
    const std::unique_ptr<InstancedAccelerator> accel = builtAtTimeZero(scene, "embree", envWithQuality("medium"));
    std::vector<Ray> rays = raysInto(scene.world, 600, 4);
    rays[5].tmin = -1.0f;  // one in parts, amid the stream
    std::vector<Hit> hits(rays.size());
    std::vector<uint8_t> occluded(rays.size());
    QueryCounters batchCounters;
    accel->findNearestBatch(rays, hits, batchCounters, {}, RayCoherence::Incoherent);
    accel->isOccludedBatch(rays, occluded, batchCounters, {}, RayCoherence::Incoherent);
    EXPECT_EQ(batchCounters.queries, 2 * rays.size());
    size_t found = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        QueryCounters counters;
        Hit hit;
        const bool single = accel->findNearest(rays[i], hit, counters);
        ASSERT_EQ(hits[i].found(), single) << i;
        EXPECT_TRUE(hitsAgree(hits[i], hit)) << i;
        if (single) {
            EXPECT_EQ(hits[i].primitive, hit.primitive) << i;
        }
        EXPECT_EQ(occluded[i] == 1, accel->isOccluded(rays[i], counters)) << i;
        found += single;
    }
    EXPECT_GT(found, 50u);
}

// Rays starting at a point inside the world with tmin = -1: Embree takes no negative tnear, so
// the part behind the origin is traced from a moved origin.
TEST(EmbreeInstances, RaysWithANegativeTminAnswerAsBruteForce) {
    InstancedWorld scene;
    const std::unique_ptr<InstancedAccelerator> accel = builtAtTimeZero(scene, "embree", envWithQuality("medium"));
    const std::unique_ptr<Accelerator> naive = createAccelerator("naive", Env(verify::verifyKeys()));
    naive->build(scene.world.prims());
    size_t behind = 0;
    for (Ray ray : raysInto(scene.world, 500, 5)) {
        ray.org = ray.org + ray.dir;
        ray.tmin = -1.0f;
        QueryCounters counters;
        Hit expected, got;
        const bool found = naive->findNearest(ray, expected, counters);
        ASSERT_EQ(accel->findNearest(ray, got, counters), found);
        ASSERT_TRUE(hitsAgree(got, expected)) << got.t << " " << expected.t;
        EXPECT_EQ(accel->isOccluded(ray, counters), naive->isOccluded(ray, counters));
        behind += found && expected.t < 0.0f;
    }
    EXPECT_GT(behind, 20u);
}

// An instance without a valid primitive has nothing for Embree to place: it is left out of the
// top scene, and the others' answers and moves are as without it.
TEST(EmbreeInstances, AnInstanceWithoutPrimitivesIsLeftOut) {
    InstancedWorld scene;
    scene.place(placements(0.0));
    std::vector<Instance> instances = scene.instances(placements(0.0));
    instances.insert(instances.begin() + 1, Instance{});
    EmbreeInstances accel(std::move(instances));
    std::vector<glm::dmat4> early = placements(1.0);
    early.insert(early.begin() + 1, glm::dmat4(1.0));
    EXPECT_THROW(accel.moveInstances(early, {}), std::logic_error);  // before build()
    accel.build({});
    expectAnswersAsBruteForce(accel, scene.world, 10);

    std::vector<glm::dmat4> moved = placements(0.75);
    EXPECT_THROW(accel.moveInstances(moved, {}), std::invalid_argument);  // one transform short
    scene.place(moved);
    moved.insert(moved.begin() + 1, glm::dmat4(1.0));
    const uint32_t missing[] = {uint32_t(moved.size())};
    EXPECT_THROW(accel.moveInstances(moved, missing), std::invalid_argument);  // no such instance
    accel.moveInstances(moved, {});
    expectAnswersAsBruteForce(accel, scene.world, 11);
}

TEST(EmbreeInstances, ReportsInstancesPrimitivesAndEmbreesBytes) {
    InstancedWorld scene;
    const std::unique_ptr<InstancedAccelerator> accel = builtAtTimeZero(scene, "embree", envWithQuality("medium"));
    const BuildStats stats = statisticsOf(*accel);
    EXPECT_EQ(stats.primitives, scene.world.valid.size());
    ASSERT_TRUE(stats.bytes.has_value());
    EXPECT_GT(*stats.bytes, 0u);
    EXPECT_FALSE(stats.nodes.has_value());  // Embree's trees are not visible
    const auto instances = std::find_if(stats.figures.begin(), stats.figures.end(),
                                        [](const NamedFigure& f) { return f.name == "instances"; });
    ASSERT_NE(instances, stats.figures.end());
    EXPECT_EQ(instances->value, 3.0);
}

}  // namespace
}  // namespace bvhlab::test
