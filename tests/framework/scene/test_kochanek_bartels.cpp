// Kochanek-Bartels splines: through every inner key exactly, clamped outside, Catmull-Rom with
// zero tension, continuity and bias, and rotations about one axis interpolated by angle.
#include "framework/scene/kochanek_bartels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

namespace bvhlab {
namespace {

std::vector<PositionKey> positionKeys(const std::vector<glm::dvec3>& values, double tension = 0.0) {
    std::vector<PositionKey> keys;
    for (size_t i = 0; i < values.size(); ++i) {
        PositionKey key;
        key.time = double(i) - 1.0;
        key.tension = tension;
        key.value = values[i];
        keys.push_back(key);
    }
    return keys;
}

void expectNearKb(const glm::dvec3& a, const glm::dvec3& b, double tolerance = 1e-12) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(KochanekBartels, PassesThroughInnerKeysAndClampsOutside) {
    const std::vector<glm::dvec3> values = {{5, 0, 0}, {0, 1, 0}, {2, 3, 1}, {-1, 0, 4}, {3, 3, 3}};
    const PositionSpline spline(positionKeys(values));
    EXPECT_EQ(spline.startTime(), 0.0);
    EXPECT_EQ(spline.endTime(), 2.0);
    for (int k = 1; k <= 3; ++k) expectNearKb(spline.at(k - 1.0), values[size_t(k)]);
    expectNearKb(spline.at(-5.0), values[1]);  // the first key only shapes the tangent
    expectNearKb(spline.at(7.0), values[3]);
}

TEST(KochanekBartels, ZeroParametersAreCatmullRom) {
    const std::vector<glm::dvec3> values = {{0, 0, 0}, {1, 2, 0}, {3, 1, 0}, {4, 4, 1}};
    const PositionSpline spline(positionKeys(values));
    // Catmull-Rom at the middle of a uniformly spaced segment: (-p0 + 9 p1 + 9 p2 - p3) / 16.
    expectNearKb(spline.at(0.5), (-values[0] + 9.0 * values[1] + 9.0 * values[2] - values[3]) / 16.0);
    // Keys on a line at even spacing give a line.
    const PositionSpline line(positionKeys({{-1, 0, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}));
    expectNearKb(line.at(0.25), {0.25, 0, 0});
    expectNearKb(line.at(1.75), {1.75, 0, 0});
}

TEST(KochanekBartels, FullTensionStopsAtEveryKey) {
    const PositionSpline spline(positionKeys({{-7, 0, 0}, {0, 0, 0}, {1, 0, 0}, {9, 0, 0}}, /*tension=*/1.0));
    // Zero tangents: the Hermite basis alone, 3u^2 - 2u^3 of the step.
    expectNearKb(spline.at(0.25), {3 * 0.0625 - 2 * 0.015625, 0, 0});
}

// Two keys at one time (BART's kitchen has 7.16 twice): no NaN, and at that time the later key,
// as BART's search for the segment gives it.
TEST(KochanekBartels, KeysAtOneTime) {
    std::vector<PositionKey> keys = positionKeys({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {5, 0, 0}, {4, 0, 0}, {3, 0, 0}});
    keys[3].time = keys[2].time;
    keys[4].time = 2.0;
    keys[5].time = 3.0;
    const PositionSpline spline(keys);
    for (double t = -1.0; t <= 3.0; t += 0.125) {
        const glm::dvec3 p = spline.at(t);
        EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << t;
    }
    expectNearKb(spline.at(keys[2].time), keys[3].value);
    expectNearKb(spline.at(2.0), keys[4].value);
}

TEST(KochanekBartels, RotationsAboutOneAxisInterpolateTheAngle) {
    std::vector<RotationKey> keys;
    for (int i = 0; i < 6; ++i) {
        RotationKey key;
        key.time = i;
        key.axis = {0, 0, -2};  // need not be unit length
        key.angle = glm::radians(90.0 * i);
        keys.push_back(key);
    }
    const RotationSpline spline(keys);
    const auto expectRotation = [&](double time, double degrees) {
        const glm::dmat3 got = glm::mat3_cast(spline.at(time));
        const glm::dmat3 want = glm::mat3_cast(quaternionFromAxisAngle({0, 0, -1}, glm::radians(degrees)));
        for (int c = 0; c < 3; ++c) expectNearKb(got[c], want[c], 1e-9);
    };
    expectRotation(1.0, 90.0);
    expectRotation(1.5, 135.0);
    expectRotation(3.25, 292.5);
    expectRotation(4.0, 360.0);
    expectRotation(9.0, 360.0);
}

}  // namespace
}  // namespace bvhlab
