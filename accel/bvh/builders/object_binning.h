// The object binning of Wald (2007), shared by sahbvh (BinnedSahBuilder) and sbvh (its object
// splits). The centres of a range are binned into K equal bins along the widest axis of the
// centre box (or along all three axes, BinnedSahConfig::allAxes):
//   binID = k1 * (c - k0),  k0 = cb_min,  k1 = K * (1 - eps) / (cb_max - cb_min);
// each bin keeps the box and the count of its primitives. Sweeps from both ends over the K-1
// planes between bins give A_L, N_L, A_R, N_R; the cheapest plane by A_L*N_L + A_R*N_R wins.
// Binning runs with the SIMD layer's vector or scalar backend (config.simd), with identical
// results.
#pragma once

#include "accel/bvh/builders/split_rule.h"

#include <optional>
#include <tuple>
#include <vector>

namespace bvhlab {

// The binned SAH's own options (sahbvh's, and sbvh's for its object splits).
struct BinnedSahConfig {
    int bins = 16;         // bins per axis; more bins approach the full sweep, and bin slower
    bool allAxes = false;  // bin all three axes and take the best plane, not only the widest axis

    bool operator==(const BinnedSahConfig&) const = default;
};

namespace keys::BVH {
inline constexpr FieldKey<&BinnedSahConfig::bins> bins{"BVH::bins", 2, 256,
                                                       "sahbvh: bins per axis (Wald 2007: 16 suffices)"};
inline constexpr FieldKey<&BinnedSahConfig::allAxes> allAxes{
    "BVH::allAxes", "sahbvh: bin all three axes and take the best, not only the widest"};
}  // namespace keys::BVH
inline constexpr std::tuple kBinnedSahKeys{&keys::BVH::bins, &keys::BVH::allAxes};

// The cheapest plane of a binning, and the rule that sends a primitive to its left.
struct ObjectPlane {
    float cost;  // A_L*N_L + A_R*N_R (N as the SAH charges it: BuildConfig::sahTests)
    int axis;
    float k0, k1, maxBin;  // binID = min(k1 * (c2 - k0), K - 1), truncated; c2 = lower + upper
    uint32_t plane;        // bins [0, plane) go left

    // Wald's binID on doubled coordinates: c2 = lower + upper is twice the box centre (k0 and
    // k1 are set up for it), and c2 - k0 leaves no multiply-add for the compiler to fuse. That
    // matters: the index must come out bit for bit the same in binning and in partitioning, in
    // every SIMD backend, or a primitive would change sides. Centres are never below k0 (their
    // minimum): the clamp at 0 only keeps a bug from writing out of bounds.
    static uint32_t binOf(const PrimRef& r, int axis, float k0, float k1, float maxBin) {
        const float c2 = r.lower[axis] + r.upper[axis];
        return uint32_t(int(simd::min(simd::max((c2 - k0) * k1, 0.0f), maxBin)));
    }
    bool isLeft(const PrimRef& r) const { return binOf(r, axis, k0, k1, maxBin) < plane; }
};

class ObjectBinning {
public:
    ObjectBinning(const BuildConfig& config, const BinnedSahConfig& binned);

    // The cheapest plane over refs[range.begin, range.end), or nullopt when the centres do not
    // spread along any binned axis. The bins stay until the next call: see the boxes below.
    std::optional<ObjectPlane> bestPlane(const PrimRef* refs, const BuildRange& range);
    // The boxes of the two sides of `plane`, from the last binning (sbvh: their overlap).
    Bounds3 leftBounds(const ObjectPlane& plane) const;
    Bounds3 rightBounds(const ObjectPlane& plane) const;

private:
    struct alignas(16) Bin {
        float lower[4];  // lane 3 unused
        float upper[4];
    };
    struct AxisBinning {
        int axis;
        float k0, k1;
    };

    template <typename F>
    std::optional<ObjectPlane> bestPlaneWith(const PrimRef* refs, const BuildRange& range);
    template <typename F>
    void binOneAxis(const PrimRef* refs, const BuildRange& range, const AxisBinning& binning);
    template <typename F>
    void binAllAxes(const PrimRef* refs, const BuildRange& range, const AxisBinning (&binning)[3]);
    template <typename F>
    void sweep(int axis, ObjectPlane& best);
    Bounds3 boundsOfBins(int axis, uint32_t first, uint32_t last) const;

    Bin* binsOf(int axis) { return bins_.data() + uint32_t(axis) * binCount_; }
    const Bin* binsOf(int axis) const { return bins_.data() + uint32_t(axis) * binCount_; }
    uint32_t* countsOf(int axis) { return counts_.data() + uint32_t(axis) * binCount_; }

    BuildConfig config_;
    bool allAxes_;
    uint32_t binCount_;
    float maxBin_;           // K - 1, the clamp of binID
    std::vector<Bin> bins_;  // K bins per axis
    std::vector<uint32_t> counts_;
    std::vector<float> rightArea_;  // per plane: half area of the bins right of it
    std::vector<uint32_t> rightCount_;
};

}  // namespace bvhlab
