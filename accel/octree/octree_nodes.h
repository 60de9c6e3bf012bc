// Havran's octree (../shared/reference/spd/havran_stats_octrees.txt): every inner node has eight
// children, split by three axis-aligned planes through one point; objects are assigned to the
// children their bounding boxes touch (closed boxes: a box touching a plane goes to both sides);
// a node is a leaf when it refers to at most MO objects or lies at the maximum depth.
// - centre subdivision (his -C): the planes through the middle of the node's box;
// - adaptive subdivision (his -A, after Whang et al.'s Octree-R): per axis, of N = 10 positions
//   from the spatial median to the object median, the one of least cost
//     C = (left + cut) * (t 2 (b + c) + b c) + (right + cut) * ((a - t) 2 (b + c) + b c)
//   for a node of a x b x c split at t along a (docs/spd.md, "Havran's octrees").
// The objects are Havran's: a sphere, a cone, and a polygon, which bvhlab's loader cuts into a fan
// of triangles (octree_objects.h); a leaf refers to every triangle of its objects. The root's box
// is the objects' bounds, padded by kRootPad of the larger of its longest side and its
// coordinates: Havran's counts on tetra, whose vertices lie on the planes of centre subdivision,
// are those of a padded box (docs/spd.md).
#pragma once

#include <bvhlab/primitive_set.h>

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace bvhlab::octree {

enum class Subdivision { Centre, Adaptive };
std::optional<Subdivision> parseSubdivision(std::string_view name);

inline constexpr double kRootPad = 1e-6;
inline constexpr int kAdaptivePositions = 10;  // Havran's N
// A bound on the references a build makes (summed over every node's list), beyond which nodes
// become leaves: bounded time and memory on any input.
inline constexpr uint64_t kMinReferenceBudget = uint64_t(1) << 24;
inline constexpr uint64_t kReferencesPerPrimitive = 32;

struct OctreeParameters {
    Subdivision subdivision = Subdivision::Centre;
    int maxDepth = 5;
    int maxObjects = 1;    // MO
    bool polygons = true;  // a fan of triangles is one object (false: every primitive is one)
};

// An inner node's children are nodes[firstChild + c], c's bit a set for the side above split[a];
// a leaf (firstChild 0: the root is no one's child) refers to `objects` objects, whose primitives
// are refs[begin .. end).
struct OctreeNode {
    DVec3 split{0.0};
    uint32_t firstChild = 0;
    uint32_t begin = 0, end = 0;
    uint32_t objects = 0;
    bool isLeaf() const { return firstChild == 0; }
    uint32_t references() const { return end - begin; }
};

struct Octree {
    DVec3 lower{0.0}, upper{0.0};   // the root's box
    std::vector<OctreeNode> nodes;  // empty: nothing to trace
    std::vector<uint32_t> refs;     // primitives, leaf by leaf
    uint64_t objects = 0;           // built over
    uint64_t objectReferences = 0;  // Havran's N_OIV
    int deepestLeaf = 0;
    bool budgetReached = false;  // some nodes became leaves because the reference budget ran out

    View<const uint32_t> leafReferences(const OctreeNode& leaf) const {
        return {refs.data() + leaf.begin, leaf.references()};
    }
    // Havran's structure figures: N_IN inner nodes, N_V leaves, N_EV empty leaves, N_OIV references.
    uint64_t innerNodes() const { return nodes.empty() ? 0 : (nodes.size() - 1) / 8; }
    uint64_t leaves() const { return nodes.size() - innerNodes(); }
    uint64_t emptyLeaves() const;
    uint64_t references() const { return objectReferences; }
    size_t maxLeafReferences() const;
    size_t bytes() const { return nodes.size() * sizeof(OctreeNode) + refs.size() * sizeof(uint32_t); }
};

Octree buildOctree(const PrimitiveSet& prims, const OctreeParameters& parameters);

// The split position of adaptive subdivision along `axis` of the node [lo, hi] referring to
// `objects` (boxes[o] the box of object o): of the N positions evenly spaced from the node's
// middle to the median of the objects' box centres (both included), the first of least cost.
// Positions on or outside the node's faces are skipped, so no child is flat.
double adaptiveSplit(View<const Bounds3> boxes, View<const uint32_t> objects, const DVec3& lo, const DVec3& hi,
                     int axis);

}  // namespace bvhlab::octree
