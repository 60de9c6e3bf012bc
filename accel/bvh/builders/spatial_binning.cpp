#include "accel/bvh/builders/spatial_binning.h"

#include "accel/bvh/builders/reference_split.h"

#include <algorithm>
#include <cmath>

namespace bvhlab {

SpatialBinning::SpatialBinning(const BuildConfig& config, int bins)
    : config_(config),
      binCount_(uint32_t(std::max(bins, 2))),
      bins_(binCount_),
      rightBox_(binCount_),
      entries_(binCount_),
      exits_(binCount_),
      rightCount_(binCount_) {}

// A reference spanning bins first..last is chopped at each plane between them in turn, its
// part in each bin growing that bin.
void SpatialBinning::binAxis(std::span<const PrimRef> refs, std::span<const Triangle> triangles,
                             const SpatialPlane& b) {
    std::fill(bins_.begin(), bins_.end(), Bounds3());
    std::fill(entries_.begin(), entries_.end(), 0u);
    std::fill(exits_.begin(), exits_.end(), 0u);
    const float binWidth = 1.0f / b.k1;
    for (const PrimRef& ref : refs) {
        const uint32_t first = b.binOf(ref.lower[b.axis]), last = b.binOf(ref.upper[b.axis]);
        ++entries_[first];
        ++exits_[last];
        Bounds3 rest = ref.box();
        for (uint32_t k = first; k < last && !rest.isEmpty(); ++k) {
            const auto [inBin, beyond] =
                splitReference(triangles[ref.prim], rest, b.axis, b.k0 + float(k + 1) * binWidth);
            if (!inBin.isEmpty()) bins_[k].extend(inBin);
            rest = beyond;
        }
        if (!rest.isEmpty()) bins_[last].extend(rest);
    }
}

// Right to left for A_R and N_R per plane, then left to right pricing every plane whose cut
// references fit in the budget.
void SpatialBinning::sweep(SpatialPlane b, uint32_t refCount, uint32_t budget, std::optional<SpatialPlane>& best) {
    Bounds3 box;
    uint32_t count = 0;
    for (uint32_t p = binCount_ - 1; p > 0; --p) {
        box.extend(bins_[p]);
        count += exits_[p];
        rightBox_[p] = box;
        rightCount_[p] = count;
    }
    box = Bounds3();
    count = 0;
    const float binWidth = 1.0f / b.k1;
    for (uint32_t p = 1; p < binCount_; ++p) {
        box.extend(bins_[p - 1]);
        count += entries_[p - 1];
        const uint32_t right = rightCount_[p];
        if (count == 0 || right == 0 || count + right - refCount > budget) continue;
        const float cost =
            box.halfArea() * float(config_.sahTests(count)) + rightBox_[p].halfArea() * float(config_.sahTests(right));
        if (best && !(cost < best->cost)) continue;
        b.cost = cost;
        b.plane = p;
        b.position = b.k0 + float(p) * binWidth;
        b.left = box;
        b.right = rightBox_[p];
        b.leftCount = count;
        b.rightCount = right;
        best = b;
    }
}

std::optional<SpatialPlane> SpatialBinning::bestPlane(std::span<const PrimRef> refs, const Bounds3& bounds,
                                                      std::span<const Triangle> triangles, uint32_t budget) {
    std::optional<SpatialPlane> best;
    for (int axis = 0; axis < 3; ++axis) {
        const float extent = bounds.upper[axis] - bounds.lower[axis];
        const float k1 = float(binCount_) / extent;
        if (!(extent > 0.0f) || !std::isfinite(k1)) continue;
        const SpatialPlane binning{kInfinity, axis, 0, bounds.lower[axis], k1, float(binCount_ - 1), 0.0f, {},
                                   {},        0,    0};
        binAxis(refs, triangles, binning);
        sweep(binning, uint32_t(refs.size()), budget, best);
    }
    return best;
}

}  // namespace bvhlab
