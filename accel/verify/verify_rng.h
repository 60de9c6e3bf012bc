// The random numbers of verification: of the generated scenes, rays and watertightness probes.
// SplitMix64, small and fast, and the same sequence on every platform and standard library
// (std::*_distribution are not), so a seed names the same rays everywhere.
#pragma once

#include <bvhlab/math.h>

#include <cmath>
#include <cstdint>

namespace bvhlab::verify {

class VerifyRng {
public:
    explicit VerifyRng(uint64_t seed) : state_(seed) {}
    uint64_t next() {
        uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    double logUniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
    size_t index(size_t n) { return size_t(uniform() * double(n)) % n; }
    bool chance(double p) { return uniform() < p; }
    // Braced, so the three coordinates are drawn in order (x, y, z) by every compiler.
    Vec3 inBox(const Bounds3& b) {
        return {float(uniform(b.lower.x, b.upper.x)), float(uniform(b.lower.y, b.upper.y)),
                float(uniform(b.lower.z, b.upper.z))};
    }
    // A point in a random direction at a uniform distance up to `radius` from the origin.
    Vec3 pointWithin(double radius) { return Vec3(unitVector() * (radius * uniform())); }
    DVec3 unitVector() {
        for (;;) {
            const DVec3 v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
            const double l2 = v.x * v.x + v.y * v.y + v.z * v.z;
            if (l2 > 1e-6 && l2 <= 1.0) return v / std::sqrt(l2);
        }
    }

private:
    uint64_t state_;
};

}  // namespace bvhlab::verify
