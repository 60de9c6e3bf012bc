// Camera rays and the camera chosen for scenes without one.
#include "accel/verify/verify_keys.h"
#include "framework/core/error.h"
#include "framework/render/camera.h"
#include "framework/scene/procedural.h"

#include <gtest/gtest.h>

#include <limits>

using namespace bvhlab;

TEST(Camera, CentreRayLooksAtTarget) {
    const Camera cam(CameraSpec{Vec3(1, 2, 3), Vec3(1, 2, -7), Vec3(0, 1, 0), 60.0f, 101, 51});
    const Ray r = cam.generateRay(50.5f, 25.5f);
    EXPECT_NEAR(glm::length(r.dir - Vec3(0, 0, -1)), 0.0f, 1e-6f);
    EXPECT_EQ(r.org, Vec3(1, 2, 3));
}

TEST(Camera, FieldOfViewAndOrientation) {
    const Camera cam(CameraSpec{Vec3(0), Vec3(0, 0, -1), Vec3(0, 1, 0), 90.0f, 100, 100});
    const Ray top = cam.generateRay(50.0f, 0.0f);      // top edge, middle
    const Ray right = cam.generateRay(100.0f, 50.0f);  // right edge, middle
    EXPECT_NEAR(top.dir.y / -top.dir.z, 1.0f, 1e-5f);  // tan(45 degrees)
    EXPECT_NEAR(right.dir.x / -right.dir.z, 1.0f, 1e-5f);
}

TEST(Camera, FramingViewSeesWholeSceneAtAnyScale) {
    for (float scale : {1e-2f, 1.0f, 1e3f}) {
        const Bounds3 b(Vec3(-1, 0, -2) * scale, Vec3(3, 1, 2) * scale);
        const CameraSpec spec = framingCamera(b, 45.0f, 64, 64);
        const Vec3 toCenter = glm::normalize(b.center() - spec.from);
        for (int i = 0; i < 8; ++i) {
            const Vec3 corner((i & 1) ? b.upper.x : b.lower.x, (i & 2) ? b.upper.y : b.lower.y,
                              (i & 4) ? b.upper.z : b.lower.z);
            const float angle = glm::degrees(std::acos(glm::dot(glm::normalize(corner - spec.from), toCenter)));
            EXPECT_LT(angle, 22.5f) << "scale " << scale;
        }
    }
}

TEST(Camera, EnvOverridesSceneCamera) {
    Scene scene = makeDefaultScene();
    Env env(verify::verifyKeys());
    env.setOverride("Camera::from=0 5 5");
    env.setOverride("Camera::width=32");
    const CameraSpec spec = resolveCamera(scene, env);
    EXPECT_EQ(spec.from, Vec3(0, 5, 5));
    EXPECT_EQ(spec.width, 32);
    EXPECT_EQ(spec.height, scene.camera->height);
    env.setOverride("Camera::at=0 5 5");
    EXPECT_THROW(resolveCamera(scene, env), InputError);
}

// Every render's camera passes resolveCamera, so a scene's own camera (from a reader or a
// forged scene cache entry) is held to the ranges of the env keys.
TEST(Camera, SceneCameraOutOfRangeIsRefused) {
    const Env env(verify::verifyKeys());
    for (int bad = 0; bad < 5; ++bad) {
        Scene scene;
        CameraSpec spec;
        if (bad == 0) spec.fovyDegrees = 0.0f;
        if (bad == 1) spec.fovyDegrees = std::numeric_limits<float>::quiet_NaN();
        if (bad == 2) spec.width = kMaxImageSide + 1;
        if (bad == 3) spec.height = 0;
        if (bad == 4) spec.from.x = std::numeric_limits<float>::infinity();
        scene.camera = spec;
        EXPECT_THROW(resolveCamera(scene, env), InputError) << bad;
    }
    Scene fine;
    fine.camera = CameraSpec{};
    EXPECT_NO_THROW(resolveCamera(fine, env));
}
