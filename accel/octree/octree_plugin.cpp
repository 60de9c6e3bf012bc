// The plugin's entry point: `octree`, Havran's octree, with its keys. Built as
// build/plugins/octree.so and found by name (-DASDS::type=octree); docs/spd.md measures it.
#include "accel/octree/octree_accelerator.h"
#include "accel/octree/octree_env.h"

#include <bvhlab/plugin.h>

#include <stdexcept>

namespace {

using namespace bvhlab;

Accelerator* createOctree(const PluginSettings& settings) {
    const auto subdivision = octree::parseSubdivision(settings.getText(keys::Octree::subdivision.name));
    if (!subdivision) throw std::invalid_argument("Octree::subdivision: unknown subdivision");
    const auto traversal = octree::parseTraversal(settings.getText(keys::Octree::traversal.name));
    if (!traversal) throw std::invalid_argument("Octree::traversal: unknown traversal");
    const octree::OctreeParameters parameters{*subdivision, settings.getInt(keys::Octree::maxDepth.name),
                                              settings.getInt(keys::Octree::maxObjects.name),
                                              settings.getBool(keys::Octree::polygons.name)};
    return new octree::OctreeAccelerator(parameters, *traversal);
}

}  // namespace

BVHLAB_PLUGIN(registrar) {
    using namespace bvhlab;
    registrar.addAccelerator(
        {"octree",
         "Havran's octree: centre or adaptive subdivision, objects by their boxes, Glassner's or Gargantini and "
         "Atkinson's traversal, no mailboxes; figures N_IN, N_V, N_EV, N_OIV, and after a trace N_ETS, N_EETS "
         "(a plugin: accel/octree/, docs/spd.md)",
         {keys::Octree::subdivision, keys::Octree::maxDepth, keys::Octree::maxObjects, keys::Octree::polygons,
          keys::Octree::traversal},
         createOctree});
}
