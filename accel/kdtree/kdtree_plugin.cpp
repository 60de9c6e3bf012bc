// The plugin's entry point: `kdtree`, the SAH kd-tree of Wald and Havran (2006) with Havran's
// TA_B^rec traversal, and its keys. Built as build/plugins/kdtree.so and found by name
// (-DASDS::type=kdtree); docs/builders.md measures it.
#include "accel/kdtree/kdtree_accelerator.h"
#include "accel/kdtree/kdtree_env.h"

#include <bvhlab/plugin.h>

namespace {

using namespace bvhlab;

Accelerator* createKdTree(const PluginSettings& settings) {
    kdtree::KdTreeParameters parameters;
    parameters.cTraversal = settings.getFloat(keys::KdTree::cTraversal.name);
    parameters.cIntersect = settings.getFloat(keys::KdTree::cIntersect.name);
    parameters.emptyBonus = settings.getFloat(keys::KdTree::emptyBonus.name);
    parameters.maxDepth = settings.getInt(keys::KdTree::maxDepth.name);
    return new kdtree::KdTreeAccelerator(parameters);
}

}  // namespace

BVHLAB_PLUGIN(registrar) {
    using namespace bvhlab;
    registrar.addAccelerator(
        {"kdtree",
         "SAH kd-tree of Wald and Havran 2006 (O(N log N) event sweep, perfect splits, empty-space "
         "bonus), Havran's TA_B^rec traversal (a plugin: accel/kdtree/, docs/builders.md)",
         {keys::KdTree::cTraversal, keys::KdTree::cIntersect, keys::KdTree::emptyBonus, keys::KdTree::maxDepth},
         createKdTree});
}
