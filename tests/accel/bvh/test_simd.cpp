// The SIMD layer's backends agree bit for bit: the same random lanes, NaN, infinities, signed
// zeros and denormals included, through Scalar<N> and the vector backend of N lanes (Sse,
// Avx where the target has AVX2) give the same bits for every operation.
#include "accel/bvh/simd/simd.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace bvhlab {
namespace {

float specialOrRandom(std::mt19937& rng) {
    constexpr float kSpecial[] = {0.0f, -0.0f, std::numeric_limits<float>::infinity(),
                                  -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(),
                                  std::numeric_limits<float>::denorm_min(), 1.0f, -1.0f};
    if (rng() % 4 == 0) return kSpecial[rng() % std::size(kSpecial)];
    return std::uniform_real_distribution<float>(-100.0f, 100.0f)(rng);
}

template <typename F>
void expectLanes(const F& v, const float* expected, const char* what) {
    alignas(32) float lanes[F::kLanes];
    v.storeu(lanes);
    for (int i = 0; i < F::kLanes; ++i)
        EXPECT_EQ(std::bit_cast<uint32_t>(lanes[i]), std::bit_cast<uint32_t>(expected[i])) << what << " lane " << i;
}

// Runs every operation on Vector and on Scalar<N> and compares the bits.
template <typename Vector>
void expectBackendsAgree(uint32_t seed) {
    constexpr int N = Vector::kLanes;
    using Reference = simd::Scalar<N>;
    std::mt19937 rng(seed);
    for (int round = 0; round < 2000; ++round) {
        alignas(32) float a[N], b[N];
        for (int i = 0; i < N; ++i) a[i] = specialOrRandom(rng), b[i] = specialOrRandom(rng);
        const Vector va = Vector::load(a), vb = Vector::loadu(b);
        const Reference ra = Reference::load(a), rb = Reference::loadu(b);
        alignas(32) float r[N];
        (ra + rb).storeu(r), expectLanes(va + vb, r, "+");
        (ra - rb).storeu(r), expectLanes(va - vb, r, "-");
        (ra * rb).storeu(r), expectLanes(va * vb, r, "*");
        (ra / rb).storeu(r), expectLanes(va / vb, r, "/");
        differenceOfProducts(ra, rb, rb, rb * ra).storeu(r);
        expectLanes(differenceOfProducts(va, vb, vb, vb * va), r, "differenceOfProducts");
        fmadd(ra, rb, rb * ra).storeu(r), expectLanes(fmadd(va, vb, vb * va), r, "fmadd");
        fmsub(ra, rb, rb * ra).storeu(r), expectLanes(fmsub(va, vb, vb * va), r, "fmsub");
        abs(ra).storeu(r), expectLanes(abs(va), r, "abs");
        min(ra, rb).storeu(r), expectLanes(min(va, vb), r, "min");
        max(ra, rb).storeu(r), expectLanes(max(va, vb), r, "max");
        select(ra >= rb, ra, rb).storeu(r), expectLanes(select(va >= vb, va, vb), r, "select");
        Reference::broadcast(a[0]).storeu(r), expectLanes(Vector::broadcast(a[0]), r, "broadcast");
        EXPECT_EQ(movemask(va <= vb), movemask(ra <= rb));
        EXPECT_EQ(movemask(va >= vb), movemask(ra >= rb));
        EXPECT_EQ(movemask(va < vb), movemask(ra < rb));
        EXPECT_EQ(movemask(va > vb), movemask(ra > rb));
        EXPECT_EQ(movemask(va != vb), movemask(ra != rb));
        EXPECT_EQ(movemask((va < vb) & (va != vb)), movemask((ra < rb) & (ra != rb)));
        EXPECT_EQ(movemask((va < vb) | (va > vb)), movemask((ra < rb) | (ra > rb)));
        // Truncation only where it is defined: finite values in int32's range.
        alignas(32) float c[N];
        for (int i = 0; i < N; ++i) c[i] = std::uniform_real_distribution<float>(-1e6f, 1e6f)(rng);
        int32_t kv[N], kr[N];
        Vector::load(c).truncateToInt(kv);
        Reference::load(c).truncateToInt(kr);
        for (int i = 0; i < N; ++i) EXPECT_EQ(kv[i], kr[i]) << "truncate lane " << i;
        if constexpr (N == 4) {
            alignas(32) float triangle[4] = {a[0], a[1], a[2], a[3]};
            Reference::loadLast3(triangle + 1).storeu(r), expectLanes(Vector::loadLast3(triangle + 1), r, "loadLast3");
        }
    }
}

TEST(Simd, TheNanRuleIsMinpsMaxps) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(simd::min(nan, 1.0f), 1.0f);
    EXPECT_TRUE(std::isnan(simd::min(1.0f, nan)));
    EXPECT_EQ(simd::max(nan, 1.0f), 1.0f);
    EXPECT_TRUE(std::isnan(simd::max(1.0f, nan)));
    EXPECT_TRUE(std::signbit(simd::min(0.0f, -0.0f)));
    EXPECT_FALSE(std::signbit(simd::max(-0.0f, 0.0f)));
}

// Where a*b and c*d are equal in exact arithmetic, the difference is exactly 0 (a float
// difference of rounded products need not be), and its sign is the exact one elsewhere.
TEST(Simd, DifferenceOfProductsHasTheExactSign) {
    using F = simd::Floats<4>;
    // 3 * (1/3 rounded) vs 1 * (3 * (1/3 rounded)) rounded: exact products differ by a tiny amount.
    const float third = 1.0f / 3.0f;
    alignas(16) float r[4];
    differenceOfProducts(F::broadcast(3.0f), F::broadcast(third), F::broadcast(1.0f), F::broadcast(3.0f * third)).storeu(r);
    const double exact = 3.0 * double(third) - double(3.0f * third);
    EXPECT_EQ(r[0] < 0.0f, exact < 0.0) << r[0] << " exact " << exact;
    EXPECT_EQ(r[0] == 0.0f, exact == 0.0) << r[0] << " exact " << exact;
    differenceOfProducts(F::broadcast(0.1f), F::broadcast(0.7f), F::broadcast(0.7f), F::broadcast(0.1f)).storeu(r);
    EXPECT_EQ(std::bit_cast<uint32_t>(r[0]), 0u);
}

TEST(Simd, FourLaneBackendsAgreeBitForBit) { expectBackendsAgree<simd::Floats<4>>(1); }

TEST(Simd, EightLaneBackendsAgreeBitForBit) { expectBackendsAgree<simd::Floats<8>>(2); }

}  // namespace
}  // namespace bvhlab
