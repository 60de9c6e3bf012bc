#include "accel/embree/embree_instances.h"
#include "accel/embree/embree_rays.h"

#include <embree3/rtcore.h>

#include <memory>
#include <stdexcept>

namespace bvhlab {

namespace {

// The affine `m` in Embree's RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR: its three columns, then the
// translation (glm's m[c][r] is column c, row r).
void setTransform(RTCGeometry geometry, const glm::dmat4& m) {
    float columns[12];
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) columns[3 * c + r] = float(m[c][r]);
    rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, columns);
}

}  // namespace

EmbreeInstances::EmbreeInstances(std::vector<Instance> instances, const EmbreeConfig& config)
    : instances_(std::move(instances)), config_(config), device_(config) {}

EmbreeInstances::~EmbreeInstances() = default;

void EmbreeInstances::build(const PrimitiveSet&) {
    top_.reset();
    bytes_.reset();
    scenes_.clear();
    scenes_.resize(instances_.size());
    size_t bytes = 0;
    for (size_t i = 0; i < instances_.size(); ++i) {
        scenes_[i].build(device_, config_, instances_[i].prims);
        bytes += scenes_[i].bytes().value_or(0);
    }
    EmbreeSceneHandle top = newEmbreeScene(device_, config_);
    // An instance without a valid primitive is left out: its scene has no bounds to place.
    for (size_t i = 0; i < instances_.size(); ++i) {
        if (scenes_[i].primitives() == 0) continue;
        const std::unique_ptr<RTCGeometryTy, decltype(&rtcReleaseGeometry)> geometry(
            rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_INSTANCE), &rtcReleaseGeometry);
        device_.check("rtcNewGeometry(instance)");
        rtcSetGeometryInstancedScene(geometry.get(), scenes_[i].get());
        setTransform(geometry.get(), instances_[i].objectToWorld);
        rtcCommitGeometry(geometry.get());
        rtcAttachGeometryByID(top.get(), geometry.get(), unsigned(i));
        device_.check("rtcAttachGeometry(instance)");
    }
    const int64_t before = device_.bytes();
    rtcCommitScene(top.get());
    device_.check("rtcCommitScene(top)");
    const int64_t after = device_.bytes();
    if (after > before) bytes += size_t(after - before);
    top_ = std::move(top);
    if (bytes > 0) bytes_ = bytes;
}

void EmbreeInstances::move(View<const glm::dmat4> objectToWorld, View<const uint32_t> deformed) {
    if (!top_) throw std::logic_error("EmbreeInstances::moveInstances before build()");
    // The instance scenes first: the top scene's commit reads their new bounds.
    for (uint32_t i : deformed) scenes_[i].update(device_, instances_[i].prims);
    for (size_t i = 0; i < instances_.size(); ++i) {
        instances_[i].objectToWorld = objectToWorld[i];
        place(i);
    }
    device_.check("rtcSetGeometryTransform/rtcCommitGeometry(instance)");
    rtcCommitScene(top_.get());
    device_.check("rtcCommitScene(top)");
}

void EmbreeInstances::place(size_t i) {
    if (scenes_[i].primitives() == 0) return;
    RTCGeometry geometry = rtcGetGeometry(top_.get(), unsigned(i));
    setTransform(geometry, instances_[i].objectToWorld);
    rtcCommitGeometry(geometry);
}

void EmbreeInstances::statistics(BuildStatistics& out) const {
    size_t primitives = 0;
    for (const EmbreeScene& scene : scenes_) primitives += scene.primitives();
    out.set("primitives", double(primitives));
    if (bytes_) out.set("bytes", double(*bytes_));
    out.figure("instances", double(instances_.size()), "instances under the top level");
}

// EmbreeAccelerator's queries (embree_rays.h), on the top scene: the hit's instance and its
// primitive there name the world's primitive.
bool EmbreeInstances::findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const {
    return embree::findNearest(top_.get(), ray, hit, counters,
                               [this](const RTCHit& h) { return worldPrimitive(h.instID[0], h.geomID, h.primID); });
}

bool EmbreeInstances::isOccluded(const Ray& ray, QueryCounters& counters) const {
    return embree::isOccluded(top_.get(), ray, counters);
}

void EmbreeInstances::findNearestBatch(View<const Ray> rays, View<Hit> hits, QueryCounters& counters,
                                       View<RayCost> costs, RayCoherence coherence) const {
    embree::findNearestBatch(top_.get(), rays, hits, counters, costs, coherence,
                             [this](const RTCHit& h) { return worldPrimitive(h.instID[0], h.geomID, h.primID); });
}

}  // namespace bvhlab
