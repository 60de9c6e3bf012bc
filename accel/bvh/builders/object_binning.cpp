#include "accel/bvh/builders/object_binning.h"

#include <algorithm>
#include <cmath>

namespace bvhlab {

namespace {

// Keeps the largest centre strictly inside the last bin: k1 * (cb_max - k0) = K * (1 - eps).
constexpr float kBinEpsilon = 1e-5f;

inline float halfArea(const float* lower, const float* upper) {
    const float dx = upper[0] - lower[0], dy = upper[1] - lower[1], dz = upper[2] - lower[2];
    return dx * dy + dy * dz + dz * dx;
}

// The box of the bins swept so far, grown bin by bin in lanes of F; its half area is computed
// by the same scalar code for every backend.
template <typename F>
struct GrowingBox {
    alignas(16) float lower[4] = {kInfinity, kInfinity, kInfinity, kInfinity};
    alignas(16) float upper[4] = {-kInfinity, -kInfinity, -kInfinity, -kInfinity};

    float grow(const float* binLower, const float* binUpper) {
        min(F::load(lower), F::load(binLower)).store(lower);
        max(F::load(upper), F::load(binUpper)).store(upper);
        return halfArea(lower, upper);
    }
};

// Adds a primitive's box to a bin's.
template <typename F>
inline void growBin(float* binLower, float* binUpper, F lo, F hi) {
    min(F::load(binLower), lo).store(binLower);
    max(F::load(binUpper), hi).store(binUpper);
}

}  // namespace

ObjectBinning::ObjectBinning(const BuildConfig& config, const BinnedSahConfig& binned)
    : config_(config),
      allAxes_(binned.allAxes),
      binCount_(uint32_t(std::max(binned.bins, 2))),
      maxBin_(float(binCount_ - 1)),
      bins_(3 * binCount_),
      counts_(3 * binCount_),
      rightArea_(binCount_),
      rightCount_(binCount_) {}

template <typename F>
void ObjectBinning::binOneAxis(const PrimRef* refs, const BuildRange& range, const AxisBinning& b) {
    Bin* const bins = binsOf(b.axis);
    uint32_t* const counts = countsOf(b.axis);
    const float maxBin = maxBin_;
    for (uint32_t i = range.begin; i < range.end; ++i) {
        const PrimRef& r = refs[i];
        const uint32_t k = ObjectPlane::binOf(r, b.axis, b.k0, b.k1, maxBin);
        growBin(bins[k].lower, bins[k].upper, F::load(r.lower), F::load(r.upper));
        ++counts[k];
    }
}

template <typename F>
void ObjectBinning::binAllAxes(const PrimRef* refs, const BuildRange& range, const AxisBinning (&b)[3]) {
    // Local pointers: the stores into the bins could otherwise alias this object's members.
    Bin* const bins[3] = {binsOf(0), binsOf(1), binsOf(2)};
    uint32_t* const counts[3] = {countsOf(0), countsOf(1), countsOf(2)};
    // All three bin indices at once, lane by lane the operations of binOf.
    alignas(16) const float k0s[4] = {b[0].k0, b[1].k0, b[2].k0, 0.0f};
    alignas(16) const float k1s[4] = {b[0].k1, b[1].k1, b[2].k1, 0.0f};
    const F k0 = F::load(k0s), k1 = F::load(k1s);
    const F maxBin = F::broadcast(maxBin_), zero = F::broadcast(0.0f);
    for (uint32_t i = range.begin; i < range.end; ++i) {
        const F lo = F::load(refs[i].lower), hi = F::load(refs[i].upper);
        int32_t k[4];
        min(max((lo + hi - k0) * k1, zero), maxBin).truncateToInt(k);
        for (int axis = 0; axis < 3; ++axis) {
            Bin& bin = bins[axis][k[axis]];
            growBin(bin.lower, bin.upper, lo, hi);
            ++counts[axis][k[axis]];
        }
    }
}

// Suffix sweep from the right stores A_R and N_R per plane; the prefix sweep from the left
// then prices every plane. Plane p separates bins [0, p) from [p, K). Empty bins change
// nothing (deep in the tree most of them are empty), so they are skipped.
template <typename F>
void ObjectBinning::sweep(int axis, ObjectPlane& best) {
    const Bin* bins = binsOf(axis);
    const uint32_t* counts = countsOf(axis);
    GrowingBox<F> box;
    uint32_t count = 0;
    float area = 0.0f;
    for (uint32_t p = binCount_ - 1; p > 0; --p) {
        if (counts[p] != 0) {
            count += counts[p];
            area = box.grow(bins[p].lower, bins[p].upper);
        }
        rightArea_[p] = area;
        rightCount_[p] = count;
    }
    box = GrowingBox<F>();
    count = 0;
    area = 0.0f;
    for (uint32_t p = 1; p < binCount_; ++p) {
        if (counts[p - 1] != 0) {
            count += counts[p - 1];
            area = box.grow(bins[p - 1].lower, bins[p - 1].upper);
        }
        if (count == 0 || rightCount_[p] == 0) continue;
        const float cost =
            area * float(config_.sahTests(count)) + rightArea_[p] * float(config_.sahTests(rightCount_[p]));
        if (cost < best.cost) best.cost = cost, best.axis = axis, best.plane = p;
    }
}

std::optional<ObjectPlane> ObjectBinning::bestPlane(const PrimRef* refs, const BuildRange& range) {
    return simd::withFloats4(config_.simd, [&](auto f) { return bestPlaneWith<decltype(f)>(refs, range); });
}

template <typename F>
std::optional<ObjectPlane> ObjectBinning::bestPlaneWith(const PrimRef* refs, const BuildRange& range) {
    const Bounds3& cb = range.centroidBounds;
    const uint32_t K = binCount_;

    // The axes to bin: the widest of the centre box, or every axis the centres spread along.
    // k0 and k1 are for doubled coordinates (see binOf): k0 = 2 cb_min, k1 = K(1-eps)/(2 extent).
    AxisBinning binning[3];
    bool active[3] = {false, false, false};
    for (int axis = 0; axis < 3; ++axis) {
        const float k0 = 2.0f * cb.lower[axis], extent2 = 2.0f * cb.upper[axis] - k0;
        const float k1 = float(K) * (1.0f - kBinEpsilon) / extent2;
        binning[axis] = {axis, k0, k1};
        active[axis] = extent2 > 0.0f && std::isfinite(k1);
    }
    const int widest = cb.largestAxis();
    if (!allAxes_) {
        for (int axis = 0; axis < 3; ++axis) active[axis] = active[axis] && axis == widest;
    }
    if (!active[0] && !active[1] && !active[2]) return std::nullopt;

    // All axes are binned in all-axes mode (inactive ones with k1 = 0: all in bin 0, unread).
    for (int axis = 0; axis < 3; ++axis) {
        if (allAxes_ && !active[axis]) binning[axis].k1 = 0.0f;
        if (!active[axis] && !allAxes_) continue;
        std::fill_n(binsOf(axis), K,
                    Bin{{kInfinity, kInfinity, kInfinity, 0.0f}, {-kInfinity, -kInfinity, -kInfinity, 0.0f}});
        std::fill_n(countsOf(axis), K, 0u);
    }
    if (allAxes_) {
        binAllAxes<F>(refs, range, binning);
    } else {
        binOneAxis<F>(refs, range, binning[widest]);
    }

    ObjectPlane best{kInfinity, -1, 0.0f, 0.0f, maxBin_, 0};
    for (int axis = 0; axis < 3; ++axis) {
        if (active[axis]) sweep<F>(axis, best);
    }
    if (best.axis < 0) return std::nullopt;
    best.k0 = binning[best.axis].k0;
    best.k1 = binning[best.axis].k1;
    return best;
}

Bounds3 ObjectBinning::boundsOfBins(int axis, uint32_t first, uint32_t last) const {
    Bounds3 box;
    for (uint32_t k = first; k < last; ++k) {
        const Bin& bin = binsOf(axis)[k];
        box.extend(Bounds3({bin.lower[0], bin.lower[1], bin.lower[2]}, {bin.upper[0], bin.upper[1], bin.upper[2]}));
    }
    return box;
}

Bounds3 ObjectBinning::leftBounds(const ObjectPlane& plane) const { return boundsOfBins(plane.axis, 0, plane.plane); }

Bounds3 ObjectBinning::rightBounds(const ObjectPlane& plane) const {
    return boundsOfBins(plane.axis, plane.plane, binCount_);
}

}  // namespace bvhlab
