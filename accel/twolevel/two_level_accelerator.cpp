#include "accel/twolevel/two_level_accelerator.h"

#include <bvhlab/quadric.h>

#include <glm/gtc/matrix_inverse.hpp>

namespace bvhlab {

namespace {

// The box of the valid primitives of `prims`.
Bounds3 boundsOfValid(const PrimitiveSet& prims) {
    Bounds3 box;
    for (uint32_t prim : prims.validTriangles()) box.extend(prims.triangles[prim].bounds());
    for (uint32_t prim : prims.validQuadrics()) box.extend(boundsOf(prims.quadric(prim)));
    return box;
}

// `box` carried by `m`: the box of its eight corners, rounded outward and padded by a millionth
// of its extent, which covers the rounding of a ray carried the other way in float.
Bounds3 transformedBox(const Bounds3& box, const glm::dmat4& m) {
    DVec3 lower(kInfinity), upper(-kInfinity);
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec4 p =
            m * glm::dvec4(corner & 1 ? box.upper.x : box.lower.x, corner & 2 ? box.upper.y : box.lower.y,
                           corner & 4 ? box.upper.z : box.lower.z, 1.0);
        for (int a = 0; a < 3; ++a) {
            lower[a] = math::min(lower[a], p[a]);
            upper[a] = math::max(upper[a], p[a]);
        }
    }
    const double extent = math::max(upper.x - lower.x, math::max(upper.y - lower.y, upper.z - lower.z));
    return boundsRoundedOutward(lower, upper, 1e-6 * extent);
}

}  // namespace

TwoLevelAccelerator::TwoLevelAccelerator(std::vector<Instance> instances, MakeBottom makeBottom,
                                         const BvhBuildConfig& top)
    : instances_(std::move(instances)), makeBottom_(std::move(makeBottom)), topConfig_(top) {}

void TwoLevelAccelerator::build(const PrimitiveSet&) {
    const size_t n = instances_.size();
    bottoms_.clear();
    objectBoxes_.assign(n, {});
    worldBoxes_.assign(n, {});
    placements_.assign(n, {});
    for (size_t i = 0; i < n; ++i) {
        bottoms_.push_back(makeBottom_());
        bottoms_[i]->build(instances_[i].prims);
        objectBoxes_[i] = boundsOfValid(instances_[i].prims);
        placeInstance(i);
    }
    buildTop();
}

void TwoLevelAccelerator::move(View<const glm::dmat4> objectToWorld, View<const uint32_t> deformed) {
    for (uint32_t i : deformed) {
        if (!bottoms_[i]->update(instances_[i].prims)) bottoms_[i]->build(instances_[i].prims);
        objectBoxes_[i] = boundsOfValid(instances_[i].prims);
    }
    for (size_t i = 0; i < instances_.size(); ++i) {
        instances_[i].objectToWorld = objectToWorld[i];
        placeInstance(i);
    }
    buildTop();
}

void TwoLevelAccelerator::placeInstance(size_t i) {
    const glm::dmat4& m = instances_[i].objectToWorld;
    placements_[i].worldToObject = glm::mat4x3(glm::affineInverse(m));
    worldBoxes_[i] = objectBoxes_[i].isEmpty() ? Bounds3{} : transformedBox(objectBoxes_[i], m);
}

void TwoLevelAccelerator::buildTop() {
    std::vector<PrimRef> refs;
    for (uint32_t i = 0; i < instances_.size(); ++i)
        if (!worldBoxes_[i].isEmpty()) refs.push_back(PrimRef::of(worldBoxes_[i], i));
    topNodes_.clear();
    topInstances_.clear();
    if (refs.empty()) return;
    topNodes_ = buildOverBoxes(topConfig_, refs);
    for (const PrimRef& ref : refs) topInstances_.push_back(ref.prim);
}

Ray TwoLevelAccelerator::toObject(const Ray& ray, size_t i) const {
    const glm::mat4x3& m = placements_[i].worldToObject;
    Ray local = ray;
    local.org = m * glm::vec4(ray.org, 1.0f);
    local.dir = m * glm::vec4(ray.dir, 0.0f);
    return local;
}

// Children in stored order: nearest first is not worth its cost over a few instances.
template <typename Visit>
void TwoLevelAccelerator::walk(const Ray& ray, QueryCounters& counters, Visit&& visit) const {
    const uint64_t queries = counters.queries + 1;
    if (ray.isValid() && !topNodes_.empty()) {
        uint32_t stack[kBvhMaxDepth + 1];
        int size = 0;
        stack[size++] = 0;
        bool done = false;
        while (size > 0 && !done) {
            const BvhNode& node = topNodes_[stack[--size]];
            ++counters.traversalSteps;
            double t0, t1;
            if (!clipToBox(ray, node.box().lower, node.box().upper, t0, t1)) continue;
            if (!node.isLeaf()) {
                stack[size++] = node.index + 1;
                stack[size++] = node.index;
                continue;
            }
            for (uint32_t k = node.index; k < node.index + node.count && !done; ++k) done = visit(topInstances_[k]);
        }
    }
    counters.queries = queries;
}

void TwoLevelAccelerator::statistics(BuildStatistics& out) const {
    size_t primitives = 0;
    for (const Instance& instance : instances_) primitives += instance.prims.valid.size();
    size_t leaves = 0;
    for (const BvhNode& node : topNodes_) leaves += node.isLeaf() ? 1 : 0;
    out.set("primitives", double(primitives));
    out.set("nodes", double(topNodes_.size()));
    out.set("leaves", double(leaves));
    out.set("bytes", double(topNodes_.size() * sizeof(BvhNode) + topInstances_.size() * sizeof(uint32_t) +
                            placements_.size() * sizeof(Placement)));
    out.figure("instances", double(instances_.size()), "instances under the top level");
}

bool TwoLevelAccelerator::findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const {
    Ray current = ray;
    bool found = false;
    walk(current, counters, [&](uint32_t i) {
        Hit local;
        if (bottoms_[i]->findNearest(toObject(current, i), local, counters)) {
            hit = {local.t, instances_[i].worldPrimitive(local.primitive), local.u, local.v};
            current.tmax = local.t;
            found = true;
        }
        return false;
    });
    return found;
}

bool TwoLevelAccelerator::isOccluded(const Ray& ray, QueryCounters& counters) const {
    bool occluded = false;
    walk(ray, counters, [&](uint32_t i) { return occluded = bottoms_[i]->isOccluded(toObject(ray, i), counters); });
    return occluded;
}

}  // namespace bvhlab
