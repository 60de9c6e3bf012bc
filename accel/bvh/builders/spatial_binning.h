// The spatial split binning of the SBVH (Stich et al. 2009): K equal bins over the
// node's box (not its centres) along each axis. A reference enters the bin of its lower bound
// and exits the bin of its upper bound; in every bin it spans, the bin's box grows by the box
// of the triangle's part inside that bin (reference_split.h). The plane between bins p-1 and p
// sends N_L = entries in [0, p) references left and N_R = exits in [p, K) right: the ones it
// cuts go to both sides, so N_L + N_R - N references are new.
#pragma once

#include "accel/bvh/builders/build_config.h"
#include "accel/bvh/layout/binary_bvh.h"

#include <bvhlab/prim_ref.h>

#include <optional>
#include <span>
#include <vector>

namespace bvhlab {

struct SpatialPlane {
    float cost;  // A_L*N_L + A_R*N_R, N as the SAH charges it (BuildConfig::sahTests)
    int axis;
    uint32_t plane;        // the plane between bins plane-1 and plane
    float k0, k1, maxBin;  // bin of x: min(k1 * (x - k0), K - 1), truncated
    float position;        // where the plane lies
    Bounds3 left, right;   // the two sides' boxes
    uint32_t leftCount, rightCount;

    uint32_t binOf(float x) const { return uint32_t(int(std::min(std::max((x - k0) * k1, 0.0f), maxBin))); }
};

class SpatialBinning {
public:
    // `bins` per axis: BinnedSahConfig::bins, as the object splits bin.
    SpatialBinning(const BuildConfig& config, int bins);

    // The cheapest plane over refs (bounded by `bounds`) whose new references fit in `budget`,
    // or nullopt when there is none.
    std::optional<SpatialPlane> bestPlane(std::span<const PrimRef> refs, const Bounds3& bounds,
                                          std::span<const Triangle> triangles, uint32_t budget);

private:
    void binAxis(std::span<const PrimRef> refs, std::span<const Triangle> triangles, const SpatialPlane& binning);
    void sweep(SpatialPlane binning, uint32_t refCount, uint32_t budget, std::optional<SpatialPlane>& best);

    BuildConfig config_;
    uint32_t binCount_;
    // Per bin: the box of what lies in it, how many references start and end in it; per plane:
    // the box and count of the bins right of it.
    std::vector<Bounds3> bins_, rightBox_;
    std::vector<uint32_t> entries_, exits_, rightCount_;
};

}  // namespace bvhlab
