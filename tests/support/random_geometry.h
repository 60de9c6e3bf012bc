// Random directions and float data read back as double, for the tests of the ray-primitive
// intersectors against their double references.
#pragma once

#include <bvhlab/math.h>
#include <glm/glm.hpp>

#include <cmath>
#include <random>

namespace bvhlab::test {

inline DVec3 randomUnit(std::mt19937& rng) {
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (;;) {
        const DVec3 v(U(rng), U(rng), U(rng));
        const double l = glm::length(v);
        if (l > 1e-3 && l <= 1.0) return v / l;
    }
}

// A point in a random direction at a uniform distance up to `radius` from the origin.
inline DVec3 randomPointWithin(std::mt19937& rng, double radius) {
    const DVec3 direction = randomUnit(rng);
    return direction * (radius * std::uniform_real_distribution<double>(0.0, 1.0)(rng));
}

// A size log-uniform over 1e-3 to 1e4: the scales the tests of the primitives cover.
inline double randomScale(std::mt19937& rng) {
    return std::pow(10.0, std::uniform_real_distribution<double>(0.0, 1.0)(rng) * 7 - 3);
}

// Float data as double, read back through a call the optimiser does not see into. GCC 12.2 at
// -O2 folds double(float(x)) back to x once SLP has vectorised both conversions (wrong code,
// seen in Triangle.FloatAndDoubleAgreeOnRandomCases: the reference then used the unrounded origin).
[[gnu::noipa]] inline DVec3 widen(const Vec3& v) { return DVec3(v); }

}  // namespace bvhlab::test
