// One Embree scene over a PrimitiveSet, as EmbreeAccelerator builds its only one and
// EmbreeInstances one per instance: one geometry per primitive kind over the valid primitives
// (triangles; spheres as Embree's sphere points; cones as a user geometry with our own test),
// and the map from Embree's geometry and primitive IDs back to our primitive indices.
#pragma once

#include "accel/embree/embree_device.h"

#include <bvhlab/cone.h>
#include <bvhlab/primitive_set.h>

#include <array>
#include <memory>
#include <optional>
#include <vector>

namespace bvhlab {

// Our geometries' IDs in every such scene, one per primitive kind.
inline constexpr unsigned kEmbreeTriangleGeometry = 0, kEmbreeSphereGeometry = 1, kEmbreeConeGeometry = 2;

struct EmbreeSceneRelease {
    void operator()(RTCSceneTy* scene) const;
};
using EmbreeSceneHandle = std::unique_ptr<RTCSceneTy, EmbreeSceneRelease>;

// A new scene with no geometry, its flags and build quality as `config` says: the scene of an
// EmbreeScene, and EmbreeInstances' top level.
EmbreeSceneHandle newEmbreeScene(const EmbreeDevice& device, const EmbreeConfig& config);

class EmbreeScene {
public:
    // Builds over prims.valid with the config's quality and flags, and commits. The previous
    // scene is dropped first: a failed build leaves none (queries then miss). Throws EmbreeError.
    void build(const EmbreeDevice& device, const EmbreeConfig& config, const PrimitiveSet& prims);
    // Writes the moved primitives of `prims` (the built set's index space and valid set, else
    // std::invalid_argument) into the geometries and commits the scene: Embree refits where the
    // geometries were built with RTC_BUILD_QUALITY_REFIT (Embree::quality=refit) and rebuilds
    // otherwise.
    void update(const EmbreeDevice& device, const PrimitiveSet& prims);

    RTCSceneTy* get() const { return scene_.get(); }
    explicit operator bool() const { return bool(scene_); }
    // Our primitive index of Embree's hit on primitive primID of geometry geomID.
    uint32_t primitive(unsigned geomID, unsigned primID) const { return primitiveOf_[geomID](primID); }
    size_t primitives() const { return primitives_; }  // the last build's valid primitives
    // What Embree's memory monitor saw the last build's commit keep; unset if nothing.
    std::optional<size_t> bytes() const { return bytes_; }

private:
    EmbreeSceneHandle scene_;
    // Per geometry: its primID -> our primitive index, as a table, or as an offset where the
    // geometry's primitives are consecutive ones of ours (no degenerate one left out): then a
    // hit costs no load from a table as large as the scene.
    struct PrimitiveMap {
        std::vector<uint32_t> table;
        uint32_t offset = 0;  // used when the table is empty
        uint32_t operator()(unsigned primID) const { return table.empty() ? offset + primID : table[primID]; }
        void compact();  // drops a table that is offset + primID
    };
    std::array<PrimitiveMap, 3> primitiveOf_;
    std::vector<Cone> cones_;  // the user geometry's primitives, read by its callbacks
    PrimitiveSet built_;       // the last build's or update's, whose counts an update keeps
    size_t primitives_ = 0;
    std::optional<size_t> bytes_;
};

}  // namespace bvhlab
