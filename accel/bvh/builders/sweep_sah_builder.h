// sweepbvh: full-sweep SAH, the exact reference the binning approximates. Per range and per
// axis, the primitives are sorted by centre (ties by primitive index) and every one of the
// N-1 splits between neighbours is priced A_L*N_L + A_R*N_R with exact boxes (a suffix sweep
// of the right boxes, then a prefix sweep). O(N log^2 N) overall: slow is fine here. No options
// of its own: it prices every plane, so there is nothing to tune but the shared BuildConfig.
#pragma once

#include "accel/bvh/builders/split_rule.h"

#include <vector>

namespace bvhlab {

class SweepSahBuilder final : public BvhSplitRule {
public:
    using BvhSplitRule::BvhSplitRule;

protected:
    std::optional<Split> trySplit(const BuildRange& range, bool mayBeLeaf) override;

private:
    void sortByCentre(const BuildRange& range, int axis);

    std::vector<float> rightArea_;  // rightArea_[i]: half area of the box of sorted refs [i, N)
};

}  // namespace bvhlab
