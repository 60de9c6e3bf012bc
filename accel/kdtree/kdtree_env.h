// The env keys of the `kdtree` plugin: the SAH constants and termination of Wald and Havran
// (2006), whose defaults are theirs (K_T = 15, K_I = 20, lambda = 0.8 when a side is empty).
#pragma once

#include <bvhlab/settings.h>

namespace bvhlab::keys::KdTree {
inline constexpr PluginKey cTraversal{"KdTree::cTraversal",
                                      KeyType::Float,
                                      "15",
                                      "K_T: SAH cost of one traversal step (Wald and Havran 2006: 15)",
                                      0.0,
                                      1e6};
inline constexpr PluginKey cIntersect{"KdTree::cIntersect",
                                      KeyType::Float,
                                      "20",
                                      "K_I: SAH cost of one primitive test (Wald and Havran 2006: 20); a node is split "
                                      "only where the SAH beats K_I * N",
                                      1e-6,
                                      1e6};
inline constexpr PluginKey emptyBonus{"KdTree::emptyBonus",
                                      KeyType::Float,
                                      "0.2",
                                      "the SAH of a split with an empty side is scaled by lambda = 1 - emptyBonus "
                                      "(Wald and Havran 2006: lambda 0.8); 0 = no bonus",
                                      0.0,
                                      0.9};
inline constexpr PluginKey maxDepth{"KdTree::maxDepth",
                                    KeyType::Int,
                                    "0",
                                    "deepest leaf; 0 = 8 + 1.3 log2 N for N primitives (rounded, at most 64)",
                                    0,
                                    64};
}  // namespace bvhlab::keys::KdTree
