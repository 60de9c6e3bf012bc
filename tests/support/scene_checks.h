// Checks on a Scene whose vertices were moved in place (AnimatedScene::setTime).
#pragma once

#include "framework/scene/scene.h"

#include <gtest/gtest.h>

namespace bvhlab::test {

// What setTime derives must be what a full finalize derives from the moved vertices.
inline void expectDerivedAsFinalize(const Scene& scene) {
    Scene fresh = scene;
    fresh.finalize();
    EXPECT_EQ(scene.bounds.lower, fresh.bounds.lower);
    EXPECT_EQ(scene.bounds.upper, fresh.bounds.upper);
    EXPECT_EQ(scene.validPrimitives, fresh.validPrimitives);
    for (size_t i = 0; i < scene.triangleCount(); ++i) ASSERT_EQ(scene.triangles[i].v1, fresh.triangles[i].v1) << i;
}

// A point where it should be, to within `tolerance` in each coordinate.
inline void expectVec(const Vec3& got, const Vec3& want, float tolerance = 1e-5f) {
    EXPECT_NEAR(got.x, want.x, tolerance);
    EXPECT_NEAR(got.y, want.y, tolerance);
    EXPECT_NEAR(got.z, want.z, tolerance);
}

}  // namespace bvhlab::test
