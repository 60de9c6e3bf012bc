// Render smoke tests: a lit, a shadowed and a background pixel, and the skipped-work counts.
#include "accel/naive/naive_accelerator.h"
#include "framework/render/camera.h"
#include "framework/render/pixel_sampler.h"
#include "framework/render/renderer.h"
#include "framework/scene/procedural.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace bvhlab;

namespace {

// A scene, a naive accelerator built over it, a camera and render settings: what a test renders.
struct NaiveRender {
    Scene scene;
    NaiveAccelerator accel;
    CameraSpec camera;
    RenderSettings settings;

    Framebuffer framebuffer() const { return Framebuffer(camera.width, camera.height); }
    RenderStats renderInto(Framebuffer& fb) const { return render(scene, accel, Camera(camera), settings, fb); }
};

// A floor quad (x, z in [-4, 4] at y = 0) and a floating occluder (x, z in [-1, 1] at y = 1),
// lit from (20, 10, 0), seen from straight above: the occluder's shadow falls on the floor
// at x in about [-3.3, -1.1].
struct ShadowScene : NaiveRender {
    ShadowScene() {
        scene.materials = {{Vec3(0.5f), 0.0f}};
        addQuad(scene, Vec3(-4, 0, -4), Vec3(0, 0, 8), Vec3(8, 0, 0), 0);
        addQuad(scene, Vec3(-1, 1, -1), Vec3(0, 0, 2), Vec3(2, 0, 0), 0);
        scene.finalize();
        accel.build(scene.primitives());
        camera = {Vec3(0, 10, 0), Vec3(0), Vec3(0, 0, -1), 90.0f, 64, 64};
        settings.threads = 2;
        settings.ambient = 0.1f;
        settings.background = Vec3(0.25f, 0.5f, 0.75f);
        settings.lights = {{Vec3(20, 10, 0), Vec3(1.0f)}};
    }

    // The pixel whose centre ray meets the plane y = 0 nearest to (x, 0, z).
    size_t pixelAt(float x, float z) const {
        const Camera cam(camera);
        size_t best = 0;
        float bestDistance = kInfinity;
        for (int py = 0; py < camera.height; ++py)
            for (int px = 0; px < camera.width; ++px) {
                const Ray r = cam.generateRay(px + 0.5f, py + 0.5f);
                const Vec3 p = r.at(-r.org.y / r.dir.y);
                const float d = glm::length(Vec3(p.x - x, 0, p.z - z));
                if (d < bestDistance) bestDistance = d, best = size_t(py) * camera.width + px;
            }
        return best;
    }
};

// Under AddressSanitizer (tests/sanitize.sh) the default scene's brute-force renders took minutes;
// at a quarter of each side they run the same code (the Release suite renders the full size).
#if defined(__SANITIZE_ADDRESS__)
constexpr int kImageDivisor = 4;
#else
constexpr int kImageDivisor = 1;
#endif

// The default scene (procedural.h) at width x height (divided by kImageDivisor), lit by its own
// lights: a scene with a mirror in view, small enough to render often.
struct SmallDefaultScene : NaiveRender {
    SmallDefaultScene(int width, int height) {
        scene = makeDefaultScene();
        accel.build(scene.primitives());
        camera = *scene.camera;
        camera.width = width / kImageDivisor;
        camera.height = height / kImageDivisor;
        settings.lights = scene.lights;
    }
};

}  // namespace

TEST(Render, LitShadowedAndBackgroundPixels) {
    ShadowScene s;
    Framebuffer fb = s.framebuffer();
    const RenderStats stats = s.renderInto(fb);

    const Vec3 ambientOnly = Vec3(0.5f) * s.settings.ambient;
    const size_t shadowed = s.pixelAt(-2.2f, 0.5f), lit = s.pixelAt(3.0f, 0.5f), background = s.pixelAt(4.8f, 4.8f);
    EXPECT_LT(glm::length(fb.color[shadowed] - ambientOnly), 1e-6f);
    EXPECT_GT(fb.color[lit].x, ambientOnly.x + 0.1f);
    EXPECT_EQ(fb.color[background], s.settings.background);
    EXPECT_LT(fb.primitive[shadowed], 2u);  // the floor
    EXPECT_LT(fb.primitive[lit], 2u);
    EXPECT_EQ(fb.primitive[background], kInvalidPrimitive);
    EXPECT_NEAR(fb.depth[lit], glm::length(Vec3(3.0f, 0, 0.5f) - s.camera.from), 0.2f);
    EXPECT_GT(fb.traversalSteps[lit], 0.0f);

    EXPECT_EQ(stats.primary.counters.queries, uint64_t(64 * 64));
    // Both quads face up and the light is above them: one shadow ray per hit pixel.
    uint64_t hitPixels = 0;
    for (uint32_t prim : fb.primitive) hitPixels += prim != kInvalidPrimitive;
    EXPECT_EQ(stats.shadow.counters.queries, hitPixels);
    EXPECT_EQ(stats.shadowRaysSkippedBackfacing, 0u);
    EXPECT_EQ(stats.threads, 2);
}

TEST(Render, ShadowsOffCastsNoShadowRays) {
    ShadowScene s;
    s.settings.shadows = false;
    Framebuffer fb = s.framebuffer();
    const RenderStats stats = s.renderInto(fb);
    EXPECT_EQ(stats.shadow.counters.queries, 0u);
    EXPECT_GT(stats.shadowRaysSkippedDisabled, 0u);
    // Without shadow rays the formerly shadowed floor is lit.
    EXPECT_GT(fb.color[s.pixelAt(-2.2f, 0.5f)].x, 0.1f);
}

TEST(Render, LightBelowSurfaceSkipsShadowRays) {
    ShadowScene s;
    s.settings.lights = {{Vec3(0, -5, 0), Vec3(1.0f)}};
    Framebuffer fb = s.framebuffer();
    const RenderStats stats = s.renderInto(fb);
    EXPECT_EQ(stats.shadow.counters.queries, 0u);
    EXPECT_GT(stats.shadowRaysSkippedBackfacing, 0u);
}

TEST(Render, MirrorBouncesOnlyWithDepthLimit) {
    SmallDefaultScene s(48, 36);
    s.settings.depthLimit = 1;
    Framebuffer fb1 = s.framebuffer();
    const RenderStats one = s.renderInto(fb1);
    const uint64_t pixels = uint64_t(s.camera.width) * s.camera.height;
    EXPECT_EQ(one.primary.counters.queries, pixels);
    EXPECT_GT(one.bouncesSkipped, 0u);  // the default scene has a mirror in view

    s.settings.depthLimit = 2;
    Framebuffer fb2 = s.framebuffer();
    const RenderStats two = s.renderInto(fb2);
    EXPECT_EQ(two.primary.counters.queries, pixels + one.bouncesSkipped);
}

TEST(Render, ImageDoesNotDependOnThreadCount) {
    SmallDefaultScene s(40, 30);
    s.settings.samples = 4;
    s.settings.threads = 1;
    Framebuffer a = s.framebuffer(), b = s.framebuffer();
    s.renderInto(a);
    s.settings.threads = 2;
    s.renderInto(b);
    EXPECT_EQ(a.color, b.color);
}

// Every sample lies in its pixel; counts that fill a grid put one sample in each cell; other
// counts are jittered over the whole pixel: over many pixels the mean offset is the centre
// (a half-filled grid would pull it towards the filled rows: the bias this guards against).
TEST(Render, TriangleWhoseNormalCannotBeNormalisedIsSkipped) {
    // A sliver of height 1e-40 (its cross product is a denormal whose square is 0), hit dead on
    // by the one pixel's ray: exactly (0, 0, -1) through the sliver's inside. Shading it would
    // normalise a NaN normal and cast NaN to int when offsetting the shadow ray.
    Scene scene;
    scene.positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, 1e-40f, 0}};
    scene.indices = {{0, 1, 2}};
    scene.finalize();
    EXPECT_EQ(scene.report.degenerateTriangles, 1u);

    NaiveAccelerator accel;
    accel.build(scene.primitives());
    RenderSettings settings;
    settings.lights = {{Vec3(0.5f, 0, 5), Vec3(1.0f)}};
    Framebuffer fb(1, 1);
    render(scene, accel, Camera(CameraSpec{Vec3(0.5f, 5e-41f, 1), Vec3(0.5f, 5e-41f, 0), Vec3(0, 1, 0), 45.0f, 1, 1}),
           settings, fb);
    EXPECT_EQ(fb.primitive[0], kInvalidPrimitive);
    EXPECT_TRUE(isFinite(fb.color[0])) << fb.color[0].x;
}

TEST(PixelSampler, StratifiedWhereAGridFillsUnbiasedElsewhere) {
    for (int count : {1, 2, 3, 4, 5, 6, 8, 9, 12, 16, 32, 64}) {
        SCOPED_TRACE(count);
        const int nx = int(std::ceil(std::sqrt(float(count)))), ny = (count + nx - 1) / nx;
        const bool grid = count > 1 && nx * ny == count;
        double sumX = 0, sumY = 0;
        const int pixels = 4000;
        for (uint32_t pixel = 0; pixel < uint32_t(pixels); ++pixel) {
            std::vector<int> perCell(size_t(nx * ny), 0);
            for (int s = 0; s < count; ++s) {
                const glm::vec2 o = sampleOffset(pixel, s, count);
                ASSERT_TRUE(o.x >= 0.0f && o.x < 1.0f && o.y >= 0.0f && o.y < 1.0f) << o.x << " " << o.y;
                sumX += o.x;
                sumY += o.y;
                ++perCell[size_t(int(o.y * float(ny)) * nx + int(o.x * float(nx)))];
            }
            if (grid) {
                for (int c : perCell) ASSERT_EQ(c, 1) << "pixel " << pixel;
            }
        }
        // 4000 pixels x count samples of a uniform [0, 1): the mean's standard deviation is at
        // most 0.29 / sqrt(4000) = 0.0046; a half-filled grid's bias is ~0.1 or more.
        const double n = double(pixels) * count;
        EXPECT_NEAR(sumX / n, 0.5, 0.02);
        EXPECT_NEAR(sumY / n, 0.5, 0.02);
    }
}
