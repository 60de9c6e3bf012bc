// sahbvh: binned SAH as Wald (2007) describes it (the binning: object_binning.h). Per range the
// cheapest plane of the binning wins, and the range is partitioned in place around it, with
// the SIMD layer's vector or scalar backend (BuildConfig::simd), with identical results. Its own
// options: BinnedSahConfig (object_binning.h).
#pragma once

#include "accel/bvh/builders/object_binning.h"
#include "accel/bvh/builders/split_rule.h"

namespace bvhlab {

class BinnedSahBuilder final : public BvhSplitRule {
public:
    BinnedSahBuilder(const BuildConfig& config, const BinnedSahConfig& binned)
        : BvhSplitRule(config), binning_(config, binned) {}

protected:
    std::optional<Split> trySplit(const BuildRange& range, bool mayBeLeaf) override;

private:
    ObjectBinning binning_;
};

}  // namespace bvhlab
