// Random directions and float data read back as double, for the tests of the ray-primitive
// intersectors against their double references.
#pragma once

#include "framework/core/math.h"

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

// Float data as double, read back through a call the optimiser does not see into. GCC 12.2 at
// -O2 folds double(float(x)) back to x once SLP has vectorised both conversions (wrong code,
// seen in Triangle.FloatAndDoubleAgreeOnRandomCases: the reference then used the unrounded origin).
[[gnu::noinline]] inline DVec3 widen(const Vec3& v) { return DVec3(v); }

}  // namespace bvhlab::test
