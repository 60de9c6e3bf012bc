// Brute force: every query tests every valid primitive. Slow and obviously right, it is the
// reference every other accelerator is tested against.
#pragma once

#include "framework/core/accelerator.h"

#include <vector>

namespace bvhlab {

class NaiveAccelerator final : public BuildStatsAccelerator {
public:
    const char* name() const override { return "naive"; }
    void build(const PrimitiveSet& prims) override;
    // Brute force over the moved primitives: the new views are all there is to update.
    bool update(const PrimitiveSet& prims) override {
        prims_ = prims;
        return true;
    }
    BuildStats buildStats() const override;
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override;
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override;

private:
    PrimitiveSet prims_;
};

}  // namespace bvhlab
