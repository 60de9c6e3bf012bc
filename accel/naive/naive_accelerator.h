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
    BuildStats buildStats() const override;
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override;
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override;

private:
    PrimitiveSet prims_;
};

}  // namespace bvhlab
