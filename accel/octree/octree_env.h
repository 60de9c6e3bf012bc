// The env keys of the `octree` plugin.
#pragma once

#include <bvhlab/settings.h>

namespace bvhlab::keys::Octree {
inline constexpr const char* kSubdivisions[] = {"centre", "adaptive"};
inline constexpr PluginKey subdivision{
    "Octree::subdivision",
    KeyType::Choice,
    "centre",
    "where a node is split: centre (Havran's -C: the middle of its box) or adaptive (-A: per axis the least of "
    "Whang's cost estimate at 10 positions between the spatial and the object median)",
    0,
    0,
    kSubdivisions};
inline constexpr PluginKey maxDepth{"Octree::maxDepth",
                                    KeyType::Int,
                                    "5",
                                    "a node at this depth is a leaf, the root at depth 0 (Havran: 4, 5, 6, 7; 5 is "
                                    "the depth of most of his best octrees)",
                                    0,
                                    12};
inline constexpr PluginKey maxObjects{"Octree::maxObjects",
                                      KeyType::Int,
                                      "1",
                                      "MO: a node referring to at most this many objects is a leaf (Havran: 1)",
                                      0,
                                      1000000};
inline constexpr PluginKey polygons{"Octree::polygons", KeyType::Bool, "true",
                                    "a polygon is one object, as in Havran's GOLEM: consecutive triangles forming a "
                                    "fan in one plane (the loader's cut of a convex polygon); false: each primitive"};
inline constexpr const char* kTraversals[] = {"octree84", "octree93"};
inline constexpr PluginKey traversal{
    "Octree::traversal",
    KeyType::Choice,
    "octree84",
    "traversal, named as Havran names them: octree84 (Glassner 1984: the leaf past each exit point located from the "
    "root down) or octree93 (Gargantini and Atkinson 1993: recursive, top down, the children in the ray's order by "
    "the parameters of their planes)",
    0,
    0,
    kTraversals};
}  // namespace bvhlab::keys::Octree
