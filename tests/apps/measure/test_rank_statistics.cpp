// Spearman's rho with ties (average ranks) and the Pareto front of `bvhlab tradeoff --builders`.
#include "apps/measure/rank_statistics.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace bvhlab;

TEST(RankStatistics, TiesGetTheAverageOfTheirRanks) {
    EXPECT_EQ(averageRanks({10.0, 20.0, 20.0, 30.0}), (std::vector<double>{1.0, 2.5, 2.5, 4.0}));
    EXPECT_EQ(averageRanks({3.0, 1.0, 3.0, 3.0}), (std::vector<double>{3.0, 1.0, 3.0, 3.0}));
    EXPECT_TRUE(averageRanks({}).empty());
}

TEST(RankStatistics, SpearmanOfMonotoneAndReversedSeries) {
    // Any increasing transform keeps the ranks.
    EXPECT_DOUBLE_EQ(*spearman({1, 2, 3, 4, 5}, {1, 8, 27, 64, 125}), 1.0);
    EXPECT_DOUBLE_EQ(*spearman({1, 2, 3, 4, 5}, {5, 4, 3, 2, 1}), -1.0);
}

TEST(RankStatistics, SpearmanWithTiesIsPearsonOfAverageRanks) {
    // x ranks 1, 2.5, 2.5, 4; y ranks 1, 2, 3, 4: rho = 4.5 / sqrt(4.5 * 5), computed by hand.
    EXPECT_NEAR(*spearman({1, 2, 2, 3}, {10, 20, 30, 40}), 4.5 / std::sqrt(4.5 * 5.0), 1e-12);
    // A textbook case without ties: 1 - 6 * sum d^2 / (n (n^2 - 1)), sum d^2 = 2 -> 0.9.
    EXPECT_NEAR(*spearman({1, 2, 3, 4, 5}, {2, 1, 3, 4, 5}), 0.9, 1e-12);
}

TEST(RankStatistics, SpearmanIsUnsetWithoutARanking) {
    EXPECT_FALSE(spearman({1}, {2}).has_value());
    EXPECT_FALSE(spearman({1, 1, 1}, {1, 2, 3}).has_value());
    EXPECT_THROW(spearman({1, 2}, {1}), std::invalid_argument);
}

TEST(RankStatistics, ParetoFrontKeepsTheUndominated) {
    //            0    1    2    3    4    5
    const std::vector<double> build = {1.0, 2.0, 3.0, 4.0, 2.0, 5.0};
    const std::vector<double> trace = {9.0, 5.0, 6.0, 2.0, 7.0, 2.0};
    // 2 is beaten by 1, 4 by 1 (same build, slower), 5 by 3 (same trace, slower build).
    EXPECT_EQ(paretoFront(build, trace), (std::vector<size_t>{0, 1, 3}));
    EXPECT_TRUE(paretoFront({}, {}).empty());
}
