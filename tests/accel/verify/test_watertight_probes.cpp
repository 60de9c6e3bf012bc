// The watertightness probes (accel/verify/watertight_probe.h): closed meshes probed as asked, rays
// through their points from outside, the same for a seed, and a test known not to be watertight
// caught.
#include "accel/bvh/bvh_env.h"
#include "tests/accel/verify/stress_fixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace bvhlab::verify {
namespace {

TEST(WatertightProbes, GeneratedMeshesAreClosedAndProbed) {
    for (const ProbedMesh& m : probedMeshes()) {
        SCOPED_TRACE(m.scene.name);
        EXPECT_TRUE(m.topology.closed()) << m.topology.summary();
        EXPECT_EQ(m.topology.faces.size(), m.scene.triangleCount());
        EXPECT_GT(m.topology.signedVolume, 0.0) << "generated meshes are wound outward";
        ASSERT_EQ(m.probes.probes.size(), 20000u);
        size_t atVertex = 0;
        for (const WatertightProbeRay& p : m.probes.probes) atVertex += p.atVertex;
        EXPECT_GT(atVertex, 4000u);
        EXPECT_LT(atVertex, 8000u);
    }
}

TEST(WatertightProbes, RaysPassThroughTheirPointFromOutside) {
    const ProbedMesh& m = probedMeshes()[0];
    const double sin6 = std::sin(6.0 * 3.14159265358979 / 180.0);
    for (size_t i = 0; i < m.probes.probes.size(); i += 7) {
        const WatertightProbeRay& p = m.probes.probes[i];
        const DVec3 org(p.ray.org), dir(p.ray.dir);
        ASSERT_NEAR(glm::length(dir), 1.0, 1e-6);
        const DVec3 toTarget = p.target - org;
        const double distance = glm::length(toTarget);
        // Within float rounding of the point, and tmax 1.0001 times its distance.
        EXPECT_LT(glm::length(glm::cross(toTarget, dir)), 1e-6 * distance) << i;
        EXPECT_NEAR(double(p.ray.tmax), 1.0001 * distance, 1e-6 * distance) << i;
        EXPECT_EQ(p.ray.tmin, 0.0f);
        // The sphere is convex: an origin on the front side of the faces is outside it.
        EXPECT_GT(glm::length(org - DVec3(0.3, -0.2, 0.1)), 1.7 * 0.99) << i;
        if (p.atVertex) {
            EXPECT_EQ(p.target, m.topology.vertices[p.feature]);
            const uint32_t v = p.feature;
            for (uint32_t k = m.topology.starOffsets[v]; k < m.topology.starOffsets[v + 1]; ++k)
                EXPECT_LT(glm::dot(m.topology.faces[m.topology.starFaces[k]].normal, dir), -sin6 * 0.999) << i;
        }
    }
}

TEST(WatertightProbes, DeterministicForASeed) {
    const Scene scene = makeTorusMesh(24, 12);
    const MeshTopology topology = MeshTopology::of(scene);
    ProbeOptions options;
    options.rays = 500;
    const ProbeSet a = makeWatertightProbes(topology, options), b = makeWatertightProbes(topology, options);
    ASSERT_EQ(a.probes.size(), b.probes.size());
    for (size_t i = 0; i < a.probes.size(); ++i) {
        EXPECT_EQ(a.probes[i].ray.org, b.probes[i].ray.org);
        EXPECT_EQ(a.probes[i].ray.dir, b.probes[i].ray.dir);
    }
    options.seed = 2;
    EXPECT_NE(makeWatertightProbes(topology, options).probes[0].ray.org, a.probes[0].ray.org);
}

// sahbvh with BVH::robust=false traverses with Moeller-Trumbore in float, which is not
// watertight: the probes must catch it (and so the switch must switch).
TEST(WatertightProbes, CatchANonWatertightTriangleTest) {
    Env env(verifyKeys());
    env.set(keys::BVH::robust, "false", "test");
    size_t leaks = 0, rays = 0;
    for (const ProbedMesh& m : probedMeshes()) {
        auto accel = createAccelerator("sahbvh", env);
        accel->build(m.scene.primitives());
        const LeakStats s = countLeaks(*accel, m.probes.probes);
        leaks += s.leaks;
        rays += s.rays;
        std::printf(
            "[ INFO     ] sahbvh, BVH::robust=false (Moeller-Trumbore) on %s: %zu leaks of %zu (edges %zu, vertices "
            "%zu)\n",
            m.scene.name.c_str(), s.leaks, s.rays, s.edgeLeaks, s.vertexLeaks);
    }
    EXPECT_GT(leaks, 0u) << "the probes did not catch a test that is known not to be watertight (" << rays << " rays)";
}

}  // namespace
}  // namespace bvhlab::verify
