// The robust box tests (box_test.h) against an exact predicate: whenever the ray's segment
// [tmin, tmax] meets a closed box, the test says so, for intervals from t = 0 and from below it
// (NegativeT), in the binary test and in every lane of the wide ones; and it is not loose: a
// box the segment misses by more than 1e-5 of its distances is culled (see axisParallel). The
// boxes are built to graze: flat, point-sized or touching the ray at a float point next to it,
// on rays with large origins and nearly axis-parallel or axis-parallel directions. Without the
// far margin (Robust = false) the same cases miss boxes: the margin is what makes the test
// conservative.
#include "accel/bvh/traverse/box_test.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <random>

namespace bvhlab {
namespace {

// p / q <= r / s in long double (64-bit significand): exact for most cases here, and where a
// product rounds, at 2^-64 of it, far below the float tests' margins (~2^-21), so it can
// never turn their answer into a failure.
bool fractionLessEqual(long double p, long double q, long double r, long double s) {
    return (q * s > 0) ? p * s <= r * q : p * s >= r * q;
}

// Whether {org + t dir : tmin <= t <= tmax} meets the closed box, exactly; `gap` receives by how
// much (relative to the larger distance) the latest entry exceeds the earliest exit (<= 0 on a hit).
bool segmentMeetsBox(const Ray& ray, const float lo[3], const float hi[3], double& gap) {
    struct Distance {
        long double num, den;  // the distance num / den
    };
    Distance entries[4], exits[4];
    int nEntries = 0, nExits = 0;
    entries[nEntries++] = {ray.tmin, 1};
    exits[nExits++] = {ray.tmax, 1};
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
        const long double o = ray.org[a], d = ray.dir[a];
        if (d == 0) {
            inside &= lo[a] <= ray.org[a] && ray.org[a] <= hi[a];
            continue;
        }
        const long double toLo = lo[a] - o, toHi = hi[a] - o;
        entries[nEntries++] = {d > 0 ? toLo : toHi, d};
        exits[nExits++] = {d > 0 ? toHi : toLo, d};
    }
    bool meets = inside;
    gap = -INFINITY;
    for (int i = 0; i < nEntries; ++i) {
        for (int j = 0; j < nExits; ++j) {
            const Distance& in = entries[i];
            const Distance& out = exits[j];
            if (std::isinf(double(out.num))) continue;  // tmax = inf
            meets &= fractionLessEqual(in.num, in.den, out.num, out.den);
            const double tin = double(in.num / in.den), tout = double(out.num / out.den);
            gap = std::max(gap, (tin - tout) / std::max({1e-30, std::abs(tin), std::abs(tout)}));
        }
    }
    if (!inside) gap = INFINITY;
    return meets;
}

// A ray, and a box grazing it: around a float point near org + t dir, flat on some axes.
struct Case {
    Ray ray;
    float lo[3], hi[3];
};

Case makeCase(std::mt19937& rng, bool negativeTmin) {
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_int_distribution<int> exponent(-3, 6);
    Case c;
    const float originScale = std::ldexp(1.0f, 3 * exponent(rng) / 2);
    for (int a = 0; a < 3; ++a) c.ray.org[a] = unit(rng) * originScale;
    for (int a = 0; a < 3; ++a) c.ray.dir[a] = unit(rng);
    // Nearly axis-parallel directions make 1/dir and org / dir large, where rounding matters most.
    const int shrink = int(rng() % 4);
    if (shrink > 0) c.ray.dir[rng() % 3] *= std::ldexp(1.0f, -8 * shrink);
    if (rng() % 16 == 0) c.ray.dir[rng() % 3] = 0.0f;
    c.ray.tmin = negativeTmin ? -std::abs(unit(rng)) * originScale : 0.0f;
    c.ray.tmax = (rng() % 8 == 0) ? kInfinity : std::abs(unit(rng)) * 4.0f * originScale;
    const float t = (rng() % 8 == 0) ? c.ray.tmin : std::abs(unit(rng)) * 2.0f * originScale;
    const float size = originScale * std::ldexp(1.0f, -int(rng() % 24));
    for (int a = 0; a < 3; ++a) {
        const float p = c.ray.org[a] + t * c.ray.dir[a];
        switch (rng() % 4) {
            case 0:
                c.lo[a] = c.hi[a] = p;
                break;  // flat
            case 1:
                c.lo[a] = p, c.hi[a] = p + std::abs(unit(rng)) * size;
                break;
            case 2:
                c.lo[a] = p - std::abs(unit(rng)) * size, c.hi[a] = p;
                break;
            default:
                c.lo[a] = std::nextafter(p, INFINITY), c.hi[a] = c.lo[a] + std::abs(unit(rng)) * size;
                break;
        }
    }
    return c;
}

std::ostream& operator<<(std::ostream& out, const Case& c) {
    const Ray& r = c.ray;
    return out << "org " << r.org[0] << " " << r.org[1] << " " << r.org[2] << " dir " << r.dir[0] << " " << r.dir[1]
               << " " << r.dir[2] << " tmin " << r.tmin << " tmax " << r.tmax << " lo " << c.lo[0] << " " << c.lo[1]
               << " " << c.lo[2] << " hi " << c.hi[0] << " " << c.hi[1] << " " << c.hi[2];
}

template <bool NegativeT, bool Robust>
bool binaryTest(const Case& c) {
    BvhNode node{};
    node.setBox({{c.lo[0], c.lo[1], c.lo[2]}, {c.hi[0], c.hi[1], c.hi[2]}});
    float entry;
    return RayBoxTest<NegativeT, Robust>(c.ray).intersect(node, c.ray.tmax, entry);
}

// Every lane of a wide node holds the same box: all must agree with the binary test.
template <int N, bool NegativeT>
int wideTest(const Case& c) {
    WideNode<N> node{};
    for (int a = 0; a < 3; ++a) {
        std::fill_n(node.lower[a], N, c.lo[a]);
        std::fill_n(node.upper[a], N, c.hi[a]);
    }
    float entry[N];
    return WideBoxTest<N, NegativeT, true>(c.ray).intersect(node, c.ray.tmax, entry);
}

// An axis-parallel ray with its origin on a slab plane gets a NaN distance there, which the
// test drops together with its neighbour in the min/max tree (box_test.h): it may keep a box it
// could cull, so the tightness check leaves such rays out.
bool axisParallel(const Ray& ray) { return ray.dir[0] == 0.0f || ray.dir[1] == 0.0f || ray.dir[2] == 0.0f; }

template <bool NegativeT>
void expectConservativeAndTight(uint32_t seed) {
    std::mt19937 rng(seed);
    int hits = 0, missedWithoutMargin = 0;
    constexpr int kCases = 400000;
    for (int i = 0; i < kCases; ++i) {
        const Case c = makeCase(rng, NegativeT);
        double gap;
        const bool exact = segmentMeetsBox(c.ray, c.lo, c.hi, gap);
        const bool binary = binaryTest<NegativeT, true>(c);
        hits += exact;
        ASSERT_EQ((wideTest<4, NegativeT>(c)), binary ? 0xf : 0) << "case " << i;
        ASSERT_EQ((wideTest<8, NegativeT>(c)), binary ? 0xff : 0) << "case " << i;
        if (exact) {
            ASSERT_TRUE(binary) << "missed a box the segment meets, case " << i << ": " << c;
            missedWithoutMargin += !binaryTest<NegativeT, false>(c);
        } else if (gap > 1e-5 && !axisParallel(c.ray)) {
            ASSERT_FALSE(binary) << "kept a box the segment misses by " << gap << ", case " << i << ": " << c;
        }
    }
    // The cases graze: a good share hits, and without the margin some of those are missed.
    EXPECT_GT(hits, kCases / 10);
    EXPECT_GT(missedWithoutMargin, 0);
    testing::Test::RecordProperty("hits", hits);
    testing::Test::RecordProperty("missedWithoutMargin", missedWithoutMargin);
}

TEST(BoxTest, NeverMissesAGrazedBox) { expectConservativeAndTight<false>(21); }
TEST(BoxTest, NeverMissesAGrazedBoxFromBelowZero) { expectConservativeAndTight<true>(22); }

}  // namespace
}  // namespace bvhlab
