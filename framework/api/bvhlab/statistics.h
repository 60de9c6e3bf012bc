// The statistics of a build, reported by name. A structure writes the figures it has and leaves
// out those it has not (they are reported as n/a, not 0). Names rather than a struct of fields:
// bvhlab adds a statistic without changing what a plugin compiled against.
#pragma once

#include <bvhlab/view.h>

#include <cstddef>

namespace bvhlab {

class BuildStatistics {
public:
    // One of the statistics bvhlab knows; any other name is refused with an error naming it.
    //   primitives                   the primitives built over (prims.valid.size())
    //   nodes, leaves                all nodes, leaves included; the leaves alone
    //   avg_leaf_prims, max_leaf_prims   primitive references per leaf, mean and largest
    //   max_depth                    the depth of the deepest leaf, the root at depth 0
    //   depth_bound, leaf_bound      the depth the structure stays below and the most
    //                                primitives a leaf holds: promises, checked by the stress tests
    //   sah, sah_c_trav, sah_c_isect the SAH cost normalised by the root box, C_trav * sum over
    //                                inner nodes of A(n)/A(root) + C_isect * sum over leaves of
    //                                A(l)/A(root) * N(l), and the two constants it was computed with
    //   epo                          end-point overlap (Aila, Karras and Laine 2013)
    //   bytes                        the memory the queries read
    virtual void set(const char* name, double value) = 0;
    // A figure of the structure's own: `name` one word, its key under "figures" in the JSON
    // ("voxels"), and `meaning` one line ("N_V, cells of the grid").
    virtual void figure(const char* name, double value, const char* meaning) = 0;
    // leavesOfSize[k]: how many leaves hold k primitives.
    virtual void leafSizes(View<const size_t> leavesOfSize) = 0;

protected:
    ~BuildStatistics() = default;
};

}  // namespace bvhlab
