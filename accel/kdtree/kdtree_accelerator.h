// The SAH kd-tree of kdtree_builder.h as an Accelerator: walked by Havran's TA_B^rec
// (kdtree_traversal.h), every reference of a leaf tested with bvhlab's watertight tests, no
// mailboxes. A plugin (kdtree_plugin.cpp), not linked into bvhlab.
#pragma once

#include "accel/kdtree/kdtree_builder.h"

#include <bvhlab/accelerator.h>

namespace bvhlab::kdtree {

class KdTreeAccelerator final : public Accelerator {
public:
    explicit KdTreeAccelerator(const KdTreeParameters& parameters) : parameters_(parameters) {}

    const char* name() const override { return "kdtree"; }
    void build(const PrimitiveSet& prims) override;
    void statistics(BuildStatistics& out) const override;
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override;
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override;

    const KdTree& tree() const { return tree_; }

private:
    KdTreeParameters parameters_;
    PrimitiveSet prims_;
    KdTree tree_;
};

}  // namespace bvhlab::kdtree
