// What `bvhlab tradeoff --builders` computes over its measurements: Spearman's rank correlation
// (does a tree metric order the builders as their trace times do?) and the Pareto front of
// build time against trace time.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace bvhlab {

// Ranks 1..n of `values`, ties given the average of the ranks they span (1, 2.5, 2.5, 4).
std::vector<double> averageRanks(const std::vector<double>& values);

// Spearman's rho: Pearson's correlation of the average ranks. Unset for fewer than two pairs
// or when either side is constant (no ranking to compare).
std::optional<double> spearman(const std::vector<double>& x, const std::vector<double>& y);

// Indices of the points no other point beats in both coordinates (smaller is better), ordered by
// x: a point is dominated when another is no worse in both and better in one.
std::vector<size_t> paretoFront(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace bvhlab
