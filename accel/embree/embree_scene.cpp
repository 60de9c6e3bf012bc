#include "accel/embree/embree_scene.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <stdexcept>

namespace bvhlab {

namespace {

static_assert(sizeof(Triangle) == 9 * sizeof(float), "a Triangle is copied as nine floats");

// Vertices are stored per triangle (3 per valid primitive) and indexed with 32-bit indices.
constexpr size_t kMaxPrimitives = std::numeric_limits<uint32_t>::max() / 3;

// The scene's build quality; the geometries' is the same but for refit, whose scene is
// two-level (LOW) over geometries built to be refitted: Embree reads a geometry's quality
// only in a scene of quality LOW.
RTCBuildQuality sceneQuality(EmbreeQuality quality) {
    switch (quality) {
        case EmbreeQuality::Low:
        case EmbreeQuality::Refit:
            return RTC_BUILD_QUALITY_LOW;
        case EmbreeQuality::Medium:
            return RTC_BUILD_QUALITY_MEDIUM;
        case EmbreeQuality::High:
            return RTC_BUILD_QUALITY_HIGH;
    }
    return RTC_BUILD_QUALITY_MEDIUM;
}
RTCBuildQuality geometryQuality(EmbreeQuality quality) {
    return quality == EmbreeQuality::Refit ? RTC_BUILD_QUALITY_REFIT : sceneQuality(quality);
}

struct GeometryDeleter {
    void operator()(RTCGeometryTy* geometry) const { rtcReleaseGeometry(geometry); }
};

// The cones as Embree's user geometry: bounds and the two queries by our own test (Embree has
// no cone; its round curves are swept spheres, not NFF's open truncated cones). Under an
// instance the rays come in the instance's object space, and the hit names the instance.
struct ConeGeometry {
    static void bounds(const RTCBoundsFunctionArguments* args) {
        const Bounds3 b = static_cast<const Cone*>(args->geometryUserPtr)[args->primID].bounds();
        *args->bounds_o = {b.lower.x, b.lower.y, b.lower.z, 0.0f, b.upper.x, b.upper.y, b.upper.z, 0.0f};
    }
    static Ray rayOf(RTCRayN* ray, unsigned n, unsigned i) {
        return {{RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i)},
                {RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i)},
                RTCRayN_tnear(ray, n, i),
                RTCRayN_tfar(ray, n, i)};
    }
    static void intersect(const RTCIntersectFunctionNArguments* args) {
        const Cone& cone = static_cast<const Cone*>(args->geometryUserPtr)[args->primID];
        RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
        RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
        for (unsigned i = 0; i < args->N; ++i) {
            if (args->valid[i] == 0) continue;
            const Ray r = rayOf(ray, args->N, i);
            QuadricHitT<float> h;
            if (!intersectCone(r, cone, r.tmin, r.tmax, h)) continue;
            RTCRayN_tfar(ray, args->N, i) = h.t;
            const RTCHit rtcHit{h.normal.x, h.normal.y,   h.normal.z,   0.0f,
                                0.0f,       args->primID, args->geomID, {args->context->instID[0]}};
            rtcCopyHitToHitN(hit, &rtcHit, args->N, i);
        }
    }
    static void occluded(const RTCOccludedFunctionNArguments* args) {
        const Cone& cone = static_cast<const Cone*>(args->geometryUserPtr)[args->primID];
        for (unsigned i = 0; i < args->N; ++i) {
            if (args->valid[i] == 0) continue;
            const Ray r = rayOf(args->ray, args->N, i);
            QuadricHitT<float> h;
            if (intersectCone(r, cone, r.tmin, r.tmax, h)) RTCRayN_tfar(args->ray, args->N, i) = -kInfinity;
        }
    }
};

// The valid triangles as geometry kEmbreeTriangleGeometry: Embree's primID i is our valid
// triangle i.
void attachTriangles(const EmbreeDevice& device, RTCScene scene, RTCBuildQuality quality, const PrimitiveSet& prims,
                     std::span<const uint32_t> validTriangles) {
    const size_t count = validTriangles.size();
    std::unique_ptr<RTCGeometryTy, GeometryDeleter> geometry(rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE));
    device.check("rtcNewGeometry");
    // Only used when the scene quality is low (two-level structure); a hint otherwise.
    rtcSetGeometryBuildQuality(geometry.get(), quality);
    // Embree-allocated buffers: Embree over-allocates the vertex buffer so that its last
    // element can be read with a 16-byte load (the padding rule shared buffers must obey).
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_VERTEX, 0,
                                                                 RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * count));
    device.check("rtcSetNewGeometryBuffer(vertex)");
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_INDEX, 0,
                                                                   RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), count));
    device.check("rtcSetNewGeometryBuffer(index)");
    // Its vertices are copied in order, so Embree's u, v are the weights of v1 and v2 as in our
    // Hit convention.
    for (size_t i = 0; i < count; ++i) {
        std::memcpy(vertices + 9 * i, &prims.triangles[validTriangles[i]], sizeof(Triangle));
        indices[3 * i + 0] = uint32_t(3 * i + 0);
        indices[3 * i + 1] = uint32_t(3 * i + 1);
        indices[3 * i + 2] = uint32_t(3 * i + 2);
    }
    rtcCommitGeometry(geometry.get());
    device.check("rtcCommitGeometry");
    rtcAttachGeometryByID(scene, geometry.get(), kEmbreeTriangleGeometry);  // the scene holds a reference
    device.check("rtcAttachGeometry");
}

// Spheres (x y z radius each) as geometry kEmbreeSphereGeometry, Embree's own point spheres.
void attachSpheres(const EmbreeDevice& device, RTCScene scene, RTCBuildQuality quality,
                   const std::vector<float>& spheres) {
    std::unique_ptr<RTCGeometryTy, GeometryDeleter> geometry(
        rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_SPHERE_POINT));
    device.check("rtcNewGeometry(sphere)");
    rtcSetGeometryBuildQuality(geometry.get(), quality);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), spheres.size() / 4));
    device.check("rtcSetNewGeometryBuffer(sphere)");
    std::copy(spheres.begin(), spheres.end(), vertices);
    rtcCommitGeometry(geometry.get());
    rtcAttachGeometryByID(scene, geometry.get(), kEmbreeSphereGeometry);
    device.check("rtcAttachGeometry(sphere)");
}

// Cones as geometry kEmbreeConeGeometry, user primitives tested by ConeGeometry; `cones` must
// outlive the scene (Embree keeps a pointer to them).
void attachCones(const EmbreeDevice& device, RTCScene scene, RTCBuildQuality quality, std::vector<Cone>& cones) {
    std::unique_ptr<RTCGeometryTy, GeometryDeleter> geometry(rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_USER));
    device.check("rtcNewGeometry(user)");
    rtcSetGeometryBuildQuality(geometry.get(), quality);
    rtcSetGeometryUserPrimitiveCount(geometry.get(), unsigned(cones.size()));
    rtcSetGeometryUserData(geometry.get(), cones.data());
    rtcSetGeometryBoundsFunction(geometry.get(), &ConeGeometry::bounds, nullptr);
    rtcSetGeometryIntersectFunction(geometry.get(), &ConeGeometry::intersect);
    rtcSetGeometryOccludedFunction(geometry.get(), &ConeGeometry::occluded);
    rtcCommitGeometry(geometry.get());
    rtcAttachGeometryByID(scene, geometry.get(), kEmbreeConeGeometry);
    device.check("rtcAttachGeometry(user)");
}

// Rewrites a geometry's vertex buffer, as its build laid it out, by write(float*), and marks it
// changed.
template <typename Write>
void rewriteVertices(RTCScene scene, unsigned geometry, Write&& write) {
    RTCGeometry g = rtcGetGeometry(scene, geometry);
    write(static_cast<float*>(rtcGetGeometryBufferData(g, RTC_BUFFER_TYPE_VERTEX, 0)));
    rtcUpdateGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(g);
}

}  // namespace

void EmbreeSceneRelease::operator()(RTCSceneTy* scene) const { rtcReleaseScene(scene); }

EmbreeSceneHandle newEmbreeScene(const EmbreeDevice& device, const EmbreeConfig& config) {
    EmbreeSceneHandle scene(rtcNewScene(device.get()));
    device.check("rtcNewScene");
    // Refit: RTC_SCENE_FLAG_DYNAMIC too, without which Embree 3.13.5 builds the geometries again at
    // every commit (an update took as long as the build on conference: 140 ms against 15).
    rtcSetSceneFlags(scene.get(), RTCSceneFlags((config.robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE) |
                                                (config.quality == EmbreeQuality::Refit ? RTC_SCENE_FLAG_DYNAMIC
                                                                                        : RTC_SCENE_FLAG_NONE)));
    rtcSetSceneBuildQuality(scene.get(), sceneQuality(config.quality));
    device.check("rtcSetSceneFlags/rtcSetSceneBuildQuality");
    return scene;
}

void EmbreeScene::PrimitiveMap::compact() {
    for (size_t i = 0; i < table.size(); ++i)
        if (table[i] != table[0] + i) return;
    offset = table.empty() ? 0 : table[0];
    table = {};
}

void EmbreeScene::build(const EmbreeDevice& device, const EmbreeConfig& config, const PrimitiveSet& prims) {
    const std::span<const uint32_t> validTriangles = prims.validTriangles();
    const size_t count = validTriangles.size();
    if (count > kMaxPrimitives)
        throw EmbreeError(
            fmt::format("Embree: {} primitives exceed the {} this binding can index", count, kMaxPrimitives));

    scene_.reset();
    built_ = prims;
    primitives_ = prims.valid.size();
    bytes_.reset();
    for (auto& map : primitiveOf_) map = {};
    primitiveOf_[kEmbreeTriangleGeometry].table.assign(validTriangles.begin(), validTriangles.end());
    cones_.clear();
    std::vector<float> spheres;  // x y z radius per sphere
    for (uint32_t prim : prims.validQuadrics()) {
        if (prims.kind(prim) == PrimitiveKind::Sphere) {
            const Sphere& s = prims.spheres[prim - prims.sphereBase()];
            // NFF's negative radius marks an inside-visible sphere; the surface is |radius|'s.
            spheres.insert(spheres.end(), {s.centre.x, s.centre.y, s.centre.z, std::abs(s.radius)});
            primitiveOf_[kEmbreeSphereGeometry].table.push_back(prim);
        } else {
            cones_.push_back(prims.cones[prim - prims.coneBase()]);
            primitiveOf_[kEmbreeConeGeometry].table.push_back(prim);
        }
    }
    for (auto& map : primitiveOf_) map.compact();
    const RTCBuildQuality quality = geometryQuality(config.quality);

    EmbreeSceneHandle scene = newEmbreeScene(device, config);

    // With no valid primitive the scene stays without geometry: committing an empty scene is
    // fine and every query then misses.
    if (count > 0) attachTriangles(device, scene.get(), quality, prims, validTriangles);
    if (!spheres.empty()) attachSpheres(device, scene.get(), quality, spheres);
    if (!cones_.empty()) attachCones(device, scene.get(), quality, cones_);
    const int64_t bytesBefore = device.bytes();
    // Embree silently skips primitives with a coordinate beyond 1.844e18 (finite ones of
    // ours included); rays can then pass through them.
    rtcCommitScene(scene.get());
    device.check("rtcCommitScene");
    const int64_t bytesAfter = device.bytes();
    scene_ = std::move(scene);
    // What Embree's memory monitor saw rtcCommitScene keep (allocated minus freed): BVH nodes
    // and Embree's own copies of the triangles in its leaves, in whole allocator blocks; not
    // our vertex and index buffers, which only copy the input.
    if (bytesAfter > bytesBefore) bytes_ = size_t(bytesAfter - bytesBefore);
}

void EmbreeScene::update(const EmbreeDevice& device, const PrimitiveSet& prims) {
    if (!scene_ || prims.triangles.size() != built_.triangles.size() || prims.spheres.size() != built_.spheres.size() ||
        prims.cones.size() != built_.cones.size() || prims.valid.size() != built_.valid.size())
        throw std::invalid_argument(fmt::format("embree: an update over {} valid primitives; built over {}",
                                                prims.valid.size(), scene_ ? built_.valid.size() : 0));
    built_ = prims;
    const std::span<const uint32_t> validTriangles = prims.validTriangles();
    if (!validTriangles.empty())
        rewriteVertices(scene_.get(), kEmbreeTriangleGeometry, [&](float* vertices) {
            for (size_t i = 0; i < validTriangles.size(); ++i)
                std::memcpy(vertices + 9 * i, &prims.triangles[validTriangles[i]], sizeof(Triangle));
        });
    const std::span<const uint32_t> quadrics = prims.validQuadrics();
    const size_t sphereCount = quadrics.size() - cones_.size();
    if (sphereCount > 0)
        rewriteVertices(scene_.get(), kEmbreeSphereGeometry, [&](float* vertices) {
            for (size_t i = 0; i < sphereCount; ++i) {
                const Sphere& s = prims.spheres[quadrics[i] - prims.sphereBase()];
                const float values[4] = {s.centre.x, s.centre.y, s.centre.z, std::abs(s.radius)};
                std::memcpy(vertices + 4 * i, values, sizeof(values));
            }
        });
    for (size_t k = 0; k < cones_.size(); ++k) cones_[k] = prims.cones[quadrics[sphereCount + k] - prims.coneBase()];
    if (!cones_.empty()) rtcCommitGeometry(rtcGetGeometry(scene_.get(), kEmbreeConeGeometry));  // bounds asked again
    device.check("rtcUpdateGeometryBuffer/rtcCommitGeometry");
    rtcCommitScene(scene_.get());
    device.check("rtcCommitScene");
}

}  // namespace bvhlab
