// The SPD rules' ray counts (framework/render/spd_tracer.h) on small scenes built in code whose
// counts follow from the rules by hand: corner rays, the depth limit, reflection and
// refraction (transmitters reflect too), shadow rays and the normal facing away, shadow rays
// from inside glass, one- and two-sided primitives. Every
// count is checked with naive and with the default BVH: the counts are invariants.
#include "accel/naive/naive_accelerator.h"
#include "accel/registry.h"
#include "accel/verify/verify_keys.h"
#include "framework/render/spd_tracer.h"

#include <gtest/gtest.h>

namespace bvhlab {
namespace {

// A quad in the plane z = height, counter-clockwise seen from +z (its outside), side 2 * half.
void addQuad(Scene& scene, float height, float half, uint32_t material, bool facingDown = false) {
    const auto base = uint32_t(scene.positions.size());
    for (const glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
        scene.positions.push_back(Vec3(half * c.x, half * c.y, height));
    if (facingDown) {
        scene.indices.push_back({base, base + 2, base + 1});
        scene.indices.push_back({base, base + 3, base + 2});
    } else {
        scene.indices.push_back({base, base + 1, base + 2});
        scene.indices.push_back({base, base + 2, base + 3});
    }
    scene.materialIds.resize(scene.indices.size(), material);
}

// A camera at `from` looking down -z (or up +z) with a narrow view: every corner ray of a
// 2 x 2 image (3 x 3 corners) stays within a few degrees of the axis.
CameraSpec cameraAt(const Vec3& from, float lookZ) {
    return CameraSpec{from, from + Vec3(0, 0, lookZ), Vec3(0, 1, 0), 10.0f, 2, 2};
}

Material matte() { return Material{.diffuse = Vec3(0.8f)}; }
Material mirror() { return Material{.diffuse = Vec3(0.2f), .mirror = 0.8f, .shine = 20.0f}; }
Material glass() {
    return Material{.diffuse = Vec3(0.1f), .mirror = 0.1f, .shine = 100.0f, .transmission = 0.9f, .ior = 1.5f};
}

SpdCounts countsWith(const Scene& scene, const Accelerator& accel, const SpdRules& rules) {
    Framebuffer fb(scene.camera->width, scene.camera->height);
    return traceSpd(scene, accel, rules, fb).counts;
}

// The counts with naive, checked equal with sahbvh8.
SpdCounts counts(const Scene& scene, SpdRules rules = {}) {
    rules.threads = 1;
    NaiveAccelerator naive;
    naive.build(scene.primitives());
    const SpdCounts expected = countsWith(scene, naive, rules);
    const auto bvh = createAccelerator("sahbvh8", Env(verify::verifyKeys()));
    bvh->build(scene.primitives());
    const SpdCounts got = countsWith(scene, *bvh, rules);
    EXPECT_EQ(got.primaryRays, expected.primaryRays);
    EXPECT_EQ(got.usedIntPrimRays, expected.usedIntPrimRays);
    EXPECT_EQ(got.shadowRays, expected.shadowRays);
    EXPECT_EQ(got.usedIntShadRays, expected.usedIntShadRays);
    EXPECT_EQ(got.secondaryRays, expected.secondaryRays);
    EXPECT_EQ(got.usedIntSecRays, expected.usedIntSecRays);
    return expected;
}

// A matte ground under a camera 5 above it, the given lights, and optionally an occluder at
// height 8 facing down.
Scene matteGround(const std::vector<PointLight>& lights, bool occluder = false) {
    Scene scene;
    scene.materials = {matte()};
    addQuad(scene, 0.0f, 100.0f, 0);
    if (occluder) addQuad(scene, 8.0f, 100.0f, 0, /*facingDown=*/true);
    scene.camera = cameraAt({0, 0, 5}, -1.0f);
    scene.lights = lights;
    scene.finalize();
    return scene;
}

TEST(SpdTracer, CornerRaysOnALitMatteGround) {
    const SpdCounts c = counts(matteGround({{Vec3(3, 4, 10), Vec3(1)}}));
    EXPECT_EQ(c.primaryRays, 9u);  // 3 x 3 corners of a 2 x 2 image
    EXPECT_EQ(c.usedIntPrimRays, 9u);
    EXPECT_EQ(c.shadowRays, 9u);
    EXPECT_EQ(c.usedIntShadRays, 0u);
    EXPECT_EQ(c.secondaryRays, 0u);  // matte: nothing to reflect
    EXPECT_EQ(c.allRays(), 18u);
    EXPECT_EQ(c.intersRequired(), 9u);
}

TEST(SpdTracer, NoShadowRayWhereTheNormalFacesAwayFromTheLight) {
    // One light below the ground, one above it.
    const SpdCounts c = counts(matteGround({{Vec3(3, 4, -10), Vec3(1)}, {Vec3(0, 0, 10), Vec3(1)}}));
    EXPECT_EQ(c.shadowRays, 9u);
    EXPECT_EQ(c.shadowRaysSkippedBackfacing, 9u);
}

TEST(SpdTracer, AnOccluderAboveTheCameraBlocksEveryShadowRay) {
    const SpdCounts c = counts(matteGround({{Vec3(0, 0, 10), Vec3(1)}}, /*occluder=*/true));
    EXPECT_EQ(c.shadowRays, 9u);
    EXPECT_EQ(c.usedIntShadRays, 9u);
}

// Two facing mirrors: every ray bounces to the depth limit (the eye ray is depth 1).
TEST(SpdTracer, ReflectionsStopAtTheTreeDepth) {
    Scene scene;
    scene.materials = {mirror()};
    addQuad(scene, 0.0f, 1000.0f, 0);
    addQuad(scene, 2.0f, 1000.0f, 0, /*facingDown=*/true);
    scene.camera = cameraAt({0, 0, 1}, -1.0f);
    scene.finalize();
    for (const int depth : {1, 2, 5}) {
        SpdRules rules;
        rules.maxDepth = depth;
        const SpdCounts c = counts(scene, rules);
        EXPECT_EQ(c.usedIntPrimRays, 9u);
        EXPECT_EQ(c.secondaryRays, 9u * uint64_t(depth - 1)) << "depth " << depth;
        EXPECT_EQ(c.usedIntSecRays, 9u * uint64_t(depth - 1));
        EXPECT_EQ(c.reflectionRays, c.secondaryRays);
        EXPECT_EQ(c.raysCutByDepth, 9u);
        EXPECT_EQ(c.shadowRays, 0u);  // no light
    }
}

// The ray tree of 9 eye rays straight through a glass solid lit from behind it, below: per eye
// ray, 8 secondary rays of which 4 hit (the counts of the two tests below), and a shadow ray
// from each of the 2 hits on the bottom from inside (the 3 other hits face away from the light).
void expectGlassTree(const SpdCounts& c, uint64_t shadowRaysOccluded) {
    EXPECT_EQ(c.usedIntPrimRays, 9u);
    EXPECT_EQ(c.secondaryRays, 9u * 8u);
    EXPECT_EQ(c.usedIntSecRays, 9u * 4u);
    EXPECT_EQ(c.shadowRays, 9u * 2u);
    EXPECT_EQ(c.shadowRaysSkippedBackfacing, 9u * 3u);
    EXPECT_EQ(c.usedIntShadRays, shadowRaysOccluded);
    EXPECT_EQ(c.raysCutByDepth, 9u * 2u);
}

// A glass sphere seen through its centre: the eye ray's hit spawns a reflection (escapes) and a
// refraction, which hits the inside and spawns an inner reflection and an exit refraction
// (escapes), and so on: at depths 1 to 4 two rays each, of which the refraction at depth 1 and
// the inner reflections at depths 2 and 3 and 4 hit; the hit at depth 5 spawns none. A light
// below: the hits on the bottom from inside (depths 2 and 4) cast shadow rays, which start
// outside a sphere (unlike a polygon's, below), toward the light, unoccluded.
TEST(SpdTracer, RefractionThroughAGlassSphere) {
    Scene scene;
    scene.materials = {glass()};
    scene.spheres = {{Vec3(0), 1.0f}};
    scene.sphereMaterialIds = {0};
    scene.camera = CameraSpec{Vec3(0, 0, 10), Vec3(0), Vec3(0, 1, 0), 0.5f, 2, 2};
    scene.lights = {{Vec3(0, 0, -10), Vec3(1)}};
    scene.finalize();
    const SpdCounts c = counts(scene);
    expectGlassTree(c, /*shadowRaysOccluded=*/0u);
    EXPECT_EQ(c.refractionRays, 9u * 4u);
    EXPECT_EQ(c.reflectionRays, 9u * 4u);
    EXPECT_EQ(c.totalInternalReflections, 0u);
}

// SPD's testing procedure: "a ray hitting a transmitting object spawns a reflection ray as
// well", whatever its Ks. A glass quad with Ks = 0 under the camera: each eye ray's hit spawns a
// reflection ray (up, into the sky) and a refraction ray (down, into nothing).
TEST(SpdTracer, ATransmitterReflectsEvenWithoutKs) {
    Scene scene;
    scene.materials = {Material{.diffuse = Vec3(0.1f), .transmission = 0.8f, .ior = 1.1f}};
    addQuad(scene, 0.0f, 100.0f, 0);
    scene.camera = cameraAt({0, 0, 5}, -1.0f);
    scene.finalize();
    const SpdCounts c = counts(scene);
    EXPECT_EQ(c.usedIntPrimRays, 9u);
    EXPECT_EQ(c.secondaryRays, 18u);
    EXPECT_EQ(c.reflectionRays, 9u);
    EXPECT_EQ(c.refractionRays, 9u);
    EXPECT_EQ(c.usedIntSecRays, 0u);
}

// A glass slab (its top facing up, its bottom down) lit from below, seen from above through
// its top. Per eye ray (depth 1, on the top from outside: the light is behind it, no shadow
// ray) the refraction (depth 2) meets the bottom from inside, and so do the inner reflections
// of depth 4; those of depth 3 and 5 meet the top from inside. Every hit but the last spawns a
// reflection and a refraction; the refractions leaving the slab hit nothing. The two hits on
// the bottom from inside cast shadow rays toward the light (the outward normal faces it),
// which start inside, as the ray came, and the bottom occludes them. Ks = 0 or not, the same.
TEST(SpdTracer, ShadowRaysFromInsideAGlassPolygonStartInside) {
    for (const float ks : {0.0f, 0.1f}) {
        SCOPED_TRACE(ks);
        Scene scene;
        scene.materials = {Material{.diffuse = Vec3(0.1f), .mirror = ks, .transmission = 0.9f, .ior = 1.5f}};
        addQuad(scene, 1.0f, 100.0f, 0);
        addQuad(scene, 0.0f, 100.0f, 0, /*facingDown=*/true);
        scene.camera = cameraAt({0, 0, 5}, -1.0f);
        scene.lights = {{Vec3(0, 0, -10), Vec3(1)}};
        scene.finalize();
        expectGlassTree(counts(scene), /*shadowRaysOccluded=*/9u * 2u);
    }
}

// Seen from behind, a one-sided quad's normal faces away from the camera and the light on the
// camera's side: no shadow ray. A two-sided scene (the teapot's rule) turns it to the viewer.
TEST(SpdTracer, OneAndTwoSidedPrimitives) {
    Scene scene;
    scene.materials = {matte()};
    addQuad(scene, 0.0f, 100.0f, 0, /*facingDown=*/true);  // its outside faces -z
    scene.camera = cameraAt({0, 0, 5}, -1.0f);
    scene.lights = {{Vec3(0, 0, 10), Vec3(1)}};
    scene.finalize();
    SpdRules rules;
    EXPECT_EQ(counts(scene, rules).shadowRays, 0u);
    rules.twoSided = true;
    EXPECT_EQ(counts(scene, rules).shadowRays, 9u);
}

TEST(SpdTracer, ASceneWithoutItsOwnViewpointIsRefused) {
    Scene scene;
    addQuad(scene, 0.0f, 1.0f, 0);
    scene.finalize();
    NaiveAccelerator naive;
    naive.build(scene.primitives());
    Framebuffer fb(2, 2);
    EXPECT_THROW(traceSpd(scene, naive, {}, fb), std::runtime_error);
}

}  // namespace
}  // namespace bvhlab
