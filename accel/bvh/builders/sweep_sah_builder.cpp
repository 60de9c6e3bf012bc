#include "accel/bvh/builders/sweep_sah_builder.h"

#include <algorithm>

namespace bvhlab {

void SweepSahBuilder::sortByCentre(const BuildRange& range, int axis) {
    std::sort(refs_.data() + range.begin, refs_.data() + range.end, [axis](const PrimRef& a, const PrimRef& b) {
        const float ca = a.center(axis), cb = b.center(axis);
        return ca < cb || (ca == cb && a.prim < b.prim);
    });
}

std::optional<Split> SweepSahBuilder::trySplit(const BuildRange& range, bool mayBeLeaf) {
    const uint32_t n = range.size();
    const PrimRef* refs = refs_.data() + range.begin;
    if (rightArea_.size() < n) rightArea_.resize(n);

    float bestCost = kInfinity;
    int bestAxis = -1, sortedAxis = -1;
    uint32_t bestCount = 0;  // primitives going left
    for (int axis = 0; axis < 3; ++axis) {
        // Along an axis where all centres coincide there is no plane between them.
        if (!(range.centroidBounds.upper[axis] > range.centroidBounds.lower[axis])) continue;
        sortByCentre(range, axis);
        sortedAxis = axis;
        Bounds3 box;
        for (uint32_t i = n - 1; i > 0; --i) {
            box.extend(Bounds3({refs[i].lower[0], refs[i].lower[1], refs[i].lower[2]},
                               {refs[i].upper[0], refs[i].upper[1], refs[i].upper[2]}));
            rightArea_[i] = box.halfArea();
        }
        box = Bounds3();
        for (uint32_t i = 1; i < n; ++i) {
            box.extend(Bounds3({refs[i - 1].lower[0], refs[i - 1].lower[1], refs[i - 1].lower[2]},
                               {refs[i - 1].upper[0], refs[i - 1].upper[1], refs[i - 1].upper[2]}));
            // Only between distinct centres: primitives with equal centres lie on the same side
            // of every plane (a split among them by index would be no plane at all).
            if (!(refs[i - 1].center(axis) < refs[i].center(axis))) continue;
            const float cost =
                box.halfArea() * float(config_.sahTests(i)) + rightArea_[i] * float(config_.sahTests(n - i));
            if (cost < bestCost) bestCost = cost, bestAxis = axis, bestCount = i;
        }
    }
    if (bestAxis < 0) return std::nullopt;
    if (mayBeLeaf && config_.sahTermination && sahPrefersLeaf(range, bestCost)) return std::nullopt;
    if (sortedAxis != bestAxis) sortByCentre(range, bestAxis);
    return splitAtIndex(range, range.begin + bestCount);
}

}  // namespace bvhlab
