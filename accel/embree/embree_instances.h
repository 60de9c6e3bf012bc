// Embree's own two levels behind InstancedAccelerator, the peer of our TwoLevelAccelerator: one
// device; per instance, one Embree scene over the instance's primitives in object space, built as
// EmbreeAccelerator builds its only one (embree_scene.h); over them a top scene of Embree
// instance geometries, one per instance, placed by its transform, with the same flags and
// quality as the instance scenes (newEmbreeScene). Embree carries a ray into an instance's object
// space itself.
//
// Moving: rigid instances get their new transforms and the top scene is committed again; a
// deformed instance's moved primitives are written into its scene's buffers and that scene is
// committed first, which Embree refits with Embree::quality=refit and rebuilds otherwise.
//
// As EmbreeAccelerator: no counters (hasCounters() is false; only counters.queries counts),
// bytes as Embree's memory monitor saw the commits keep, rays Embree cannot take traced in parts
// or missed (embree_rays.h), closest-hit batches through its stream API (any-hit ones: below).
#pragma once

#include "accel/embree/embree_device.h"
#include "accel/embree/embree_scene.h"
#include "framework/core/instanced_accelerator.h"

#include <optional>
#include <vector>

namespace bvhlab {

class EmbreeInstances final : public InstancedAccelerator {
public:
    // Creates the device; throws EmbreeError when Embree refuses.
    EmbreeInstances(std::vector<Instance> instances, const EmbreeConfig& config = {});
    ~EmbreeInstances() override;
    EmbreeInstances(const EmbreeInstances&) = delete;
    EmbreeInstances& operator=(const EmbreeInstances&) = delete;

    const char* name() const override { return "embreeinstances"; }
    void build(const PrimitiveSet& prims) override;
    size_t instanceCount() const override { return instances_.size(); }
    // The instances, their primitives summed, Embree's bytes of the last build.
    void statistics(BuildStatistics& out) const override;
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override;
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override;
    // Through rtcIntersect1M on the top scene, as EmbreeAccelerator's. Any-hit batches go ray by
    // ray (rtcOccluded1, the interface's default loop): Debian's Embree 3.13.5 never returned from
    // rtcOccluded1M over these instances on a small animated scene (a rotated instance holding a
    // sphere; `bvhlab animate --check` on tests/support/moving_scene.h), spinning in its kernels.
    void findNearestBatch(View<const Ray> rays, View<Hit> hits, QueryCounters& counters, View<RayCost> costs,
                          RayCoherence coherence) const override;
    bool hasCounters() const override { return false; }

    const EmbreeConfig& config() const { return config_; }

protected:
    void move(View<const glm::dmat4> objectToWorld, View<const uint32_t> deformed) override;

private:
    void place(size_t i);  // instance i's transform onto its geometry in the top scene
    // The world primitive of Embree's hit: primitive geomID/primID of instance instID[0].
    uint32_t worldPrimitive(unsigned instance, unsigned geomID, unsigned primID) const {
        return instances_[instance].worldPrimitive(scenes_[instance].primitive(geomID, primID));
    }

    std::vector<Instance> instances_;
    EmbreeConfig config_;
    EmbreeDevice device_;
    std::vector<EmbreeScene> scenes_;  // per instance; after device_: released before it
    EmbreeSceneHandle top_;            // after scenes_; instance i is its geometry i, if not empty
    std::optional<size_t> bytes_;
};

}  // namespace bvhlab
