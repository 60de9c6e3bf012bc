// sahbvh: binned SAH as Wald (2007) describes it (the binning: object_binning.h). Per range the
// cheapest plane of the binning wins, and the range is partitioned in place around it, with
// the SIMD layer's vector or scalar backend (config.simd), with identical results.
#pragma once

#include "accel/bvh/builders/bvh_builder.h"
#include "accel/bvh/builders/object_binning.h"

namespace bvhlab {

class BinnedSahBuilder final : public TopDownBuilder {
public:
    explicit BinnedSahBuilder(const BvhBuildConfig& config) : TopDownBuilder(config), binning_(config) {}

protected:
    std::optional<Split> trySplit(const BuildRange& range, bool mayBeLeaf) override;

private:
    ObjectBinning binning_;
};

}  // namespace bvhlab
