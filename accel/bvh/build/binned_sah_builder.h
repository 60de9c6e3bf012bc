// sahbvh: binned SAH as Wald (2007) describes it. Per range, the centres are binned into K
// equal bins along the widest axis of the centre box (or along all three axes, config.allAxes):
//   binID = k1 * (c - k0),  k0 = cb_min,  k1 = K * (1 - eps) / (cb_max - cb_min);
// each bin keeps the box and the count of its primitives. Sweeps from both ends over the K-1
// planes between bins give A_L, N_L, A_R, N_R; the cheapest plane by A_L*N_L + A_R*N_R wins,
// and the range is partitioned in place around it. Binning and partition run with the SIMD
// layer's vector or scalar backend (config.simd), with identical results.
#pragma once

#include "accel/bvh/build/bvh_builder.h"

#include <vector>

namespace bvhlab {

class BinnedSahBuilder final : public TopDownBuilder {
public:
    explicit BinnedSahBuilder(const BvhBuildConfig& config);

protected:
    std::optional<Split> trySplit(const BuildRange& range, bool mayBeLeaf) override;

private:
    struct alignas(16) Bin {
        float lower[4];  // lane 3 unused
        float upper[4];
    };
    // The binning of one axis: binID = min(k1 * (c - k0), K - 1), truncated (c: see binOf).
    struct AxisBinning {
        int axis;
        float k0, k1;
    };
    struct PlaneChoice {
        float cost;  // A_L*N_L + A_R*N_R
        int axis;
        uint32_t plane;  // bins [0, plane) go left
    };

    // The split in lanes of F (simd::Floats<4> or simd::Scalar<4>, per config.simd).
    template <typename F>
    std::optional<Split> trySplitWith(const BuildRange& range, bool mayBeLeaf);
    template <typename F>
    void binOneAxis(const BuildRange& range, const AxisBinning& binning);
    template <typename F>
    void binAllAxes(const BuildRange& range, const AxisBinning (&binning)[3]);
    template <typename F>
    void sweep(int axis, PlaneChoice& best);

    Bin* binsOf(int axis) { return bins_.data() + uint32_t(axis) * binCount_; }
    uint32_t* countsOf(int axis) { return counts_.data() + uint32_t(axis) * binCount_; }

    uint32_t binCount_;
    float maxBin_;             // K - 1, the clamp of binID
    std::vector<Bin> bins_;  // K bins per axis
    std::vector<uint32_t> counts_;
    std::vector<float> rightArea_;  // per plane: half area of the bins right of it
    std::vector<uint32_t> rightCount_;
};

}  // namespace bvhlab
