// The SIMD layer's backends agree bit for bit: the same random lanes, NaN, infinities, signed
// zeros and denormals included, through Scalar<N> and the vector backend of N lanes (Sse,
// Avx where the target has AVX2, Avx512 where it has AVX-512, and Avx512 compiled apart for
// x86-64-v4 wherever the CPU runs it) give the same bits for every operation.
#include "accel/bvh/simd/simd.h"
#include "accel/bvh/traverse/traversal_kernels.h"
#include "tests/accel/bvh/simd/simd_ops.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace bvhlab {
namespace test {
void avx512SimdOpResults(const float* a, const float* b, const float* c, uint32_t* out);
}  // namespace test
namespace {

float specialOrRandom(std::mt19937& rng) {
    constexpr float kSpecial[] = {0.0f,
                                  -0.0f,
                                  std::numeric_limits<float>::infinity(),
                                  -std::numeric_limits<float>::infinity(),
                                  std::numeric_limits<float>::quiet_NaN(),
                                  std::numeric_limits<float>::denorm_min(),
                                  1.0f,
                                  -1.0f};
    if (rng() % 4 == 0) return kSpecial[rng() % std::size(kSpecial)];
    return std::uniform_real_distribution<float>(-100.0f, 100.0f)(rng);
}

// Random lanes a, b (a fourth special values) and c (finite, for the truncation).
struct OpInputs {
    alignas(64) float a[16], b[16], c[16];

    explicit OpInputs(std::mt19937& rng) {
        for (int i = 0; i < 16; ++i) {
            a[i] = specialOrRandom(rng), b[i] = specialOrRandom(rng);
            c[i] = std::uniform_real_distribution<float>(-1e6f, 1e6f)(rng);
        }
    }
};

// Runs every operation (simd_ops.h) through `vector`, of N lanes, and through Scalar<N>, and
// compares the bits.
template <int N, typename Run>
void expectAgreesWithScalar(uint32_t seed, Run vector) {
    std::mt19937 rng(seed);
    constexpr int kCount = simdOpResultCount(N);
    for (int round = 0; round < 2000; ++round) {
        const OpInputs in(rng);
        uint32_t expected[kCount], actual[kCount];
        simdOpResults<simd::Scalar<N>>(in.a, in.b, in.c, expected);
        vector(in.a, in.b, in.c, actual);
        for (int i = 0; i < kCount; ++i) {
            EXPECT_EQ(actual[i], expected[i]) << "result " << i << " (operation " << i / N << ", simd_ops.h)";
            if (actual[i] != expected[i]) return;
        }
    }
}

template <typename Vector>
void expectBackendsAgree(uint32_t seed) {
    expectAgreesWithScalar<Vector::kLanes>(seed, simdOpResults<Vector>);
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
    differenceOfProducts(F::broadcast(3.0f), F::broadcast(third), F::broadcast(1.0f), F::broadcast(3.0f * third))
        .storeu(r);
    const double exact = 3.0 * double(third) - double(3.0f * third);
    EXPECT_EQ(r[0] < 0.0f, exact < 0.0) << r[0] << " exact " << exact;
    EXPECT_EQ(r[0] == 0.0f, exact == 0.0) << r[0] << " exact " << exact;
    differenceOfProducts(F::broadcast(0.1f), F::broadcast(0.7f), F::broadcast(0.7f), F::broadcast(0.1f)).storeu(r);
    EXPECT_EQ(std::bit_cast<uint32_t>(r[0]), 0u);
}

TEST(Simd, FourLaneBackendsAgreeBitForBit) { expectBackendsAgree<simd::Floats<4>>(1); }

TEST(Simd, EightLaneBackendsAgreeBitForBit) { expectBackendsAgree<simd::Floats<8>>(2); }

// Avx512 only where the CPU runs it (simd_ops_avx512.cpp is compiled for x86-64-v4): on other
// machines there is nothing to compare.
TEST(Simd, SixteenLaneBackendsAgreeBitForBit) {
    expectBackendsAgree<simd::Floats<16>>(3);
    if (!cpuRuns(Isa::Avx512)) {
        std::printf("[ simd     ] no AVX-512 on this CPU: Avx512 not run\n");
        return;
    }
    expectAgreesWithScalar<16>(4, test::avx512SimdOpResults);
}

}  // namespace
}  // namespace bvhlab
