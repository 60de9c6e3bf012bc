#include "accel/embree/embree_accelerator.h"
#include "framework/config/common_keys.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <immintrin.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <type_traits>

static_assert(std::is_same_v<RTCDevice, RTCDeviceTy*>, "Embree's handle types differ from the forward declarations");
static_assert(std::is_same_v<RTCScene, RTCSceneTy*>, "Embree's handle types differ from the forward declarations");

namespace bvhlab {

namespace {

static_assert(sizeof(Triangle) == 9 * sizeof(float), "a Triangle is copied as nine floats");

// Vertices are stored per triangle (3 per valid primitive) and indexed with 32-bit indices.
constexpr size_t kMaxPrimitives = std::numeric_limits<uint32_t>::max() / 3;

const char* errorName(RTCError code) {
    switch (code) {
        case RTC_ERROR_NONE:
            return "RTC_ERROR_NONE";
        case RTC_ERROR_UNKNOWN:
            return "RTC_ERROR_UNKNOWN";
        case RTC_ERROR_INVALID_ARGUMENT:
            return "RTC_ERROR_INVALID_ARGUMENT";
        case RTC_ERROR_INVALID_OPERATION:
            return "RTC_ERROR_INVALID_OPERATION";
        case RTC_ERROR_OUT_OF_MEMORY:
            return "RTC_ERROR_OUT_OF_MEMORY";
        case RTC_ERROR_UNSUPPORTED_CPU:
            return "RTC_ERROR_UNSUPPORTED_CPU";
        case RTC_ERROR_CANCELLED:
            return "RTC_ERROR_CANCELLED";
    }
    return "unknown RTCError";
}

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

// Our geometries' IDs in Embree's scene, one per primitive kind (EmbreeAccelerator::primitiveOf_).
constexpr unsigned kTriangleGeometry = 0, kSphereGeometry = 1, kConeGeometry = 2;

// The cones as Embree's user geometry: bounds and the two queries by our own test (Embree has
// no cone; its round curves are swept spheres, not NFF's open truncated cones).
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

// Largest coordinate Embree accepts in a ray (its FLT_LARGE). Debian's libembree3 is built
// with assertions enabled, and rtcIntersect1/rtcOccluded1 assert ray.valid() (|org|, |dir|
// components <= 1.844e18, so no infinities) and tnear >= 0: a ray breaking either aborts the
// process. Such rays never reach Embree.
constexpr float kEmbreeLarge = 1.844E18f;

inline bool withinEmbreeRange(const Vec3& v) {
    return std::abs(v.x) <= kEmbreeLarge && std::abs(v.y) <= kEmbreeLarge && std::abs(v.z) <= kEmbreeLarge;
}

// A ray in Embree's terms: one or two segments, each with tnear >= 0, in order of increasing t.
// Embree requires tnear >= 0 (besides the assertion, its traversal clamps the box interval at
// 0 while the triangle test uses tnear as given). A ray whose interval starts behind its
// origin is therefore traced in two parts: first [tmin, min(tmax, 0)] from the moved origin
// org + tmin*dir (tnear 0, and tmin added back to the hit distance), then, if nothing was
// found there, [0, tmax] from the original origin. Hits at t >= 0 are thus exactly as for a
// ray with tmin = 0; hits behind the origin carry the rounding of the moved origin and of the
// sum (absolute error about an ulp of |tmin|). The backward part is skipped when tmin = -inf
// (it cannot be moved to) or when the moved origin is beyond kEmbreeLarge: hits behind the
// origin are then not reported. A ray with a direction component beyond kEmbreeLarge (or
// infinite), or an origin that is, has no segments: it misses without reaching Embree.
struct Segment {
    Vec3 org;
    float tnear, tfar;
    float shift;  // add to Embree's t to get ours
};

struct Segments {
    Segment part[2];
    int count = 0;
};

inline Segments segmentsOf(const Ray& ray) {
    Segments s;
    if (!withinEmbreeRange(ray.dir)) return s;
    if (ray.tmin >= 0.0f) {
        if (withinEmbreeRange(ray.org)) s.part[s.count++] = {ray.org, ray.tmin, ray.tmax, 0.0f};
        return s;
    }
    if (std::isfinite(ray.tmin)) {
        const Vec3 moved = ray.org + ray.tmin * ray.dir;
        if (withinEmbreeRange(moved)) s.part[s.count++] = {moved, 0.0f, std::min(ray.tmax, 0.0f) - ray.tmin, ray.tmin};
    }
    if (ray.tmax >= 0.0f && withinEmbreeRange(ray.org)) s.part[s.count++] = {ray.org, 0.0f, ray.tmax, 0.0f};
    return s;
}

// Written as three 16-byte stores, the widths in which Embree reads the ray back at once: a
// ray written field by field would make those loads wait for the stores to reach the cache
// (no store-to-load forwarding from several stores into one load).
inline void toRtc(const Segment& segment, const Vec3& dir, RTCRay& r) {
    static_assert(offsetof(RTCRay, tnear) == 12 && offsetof(RTCRay, time) == 28 && offsetof(RTCRay, flags) == 44);
    _mm_store_ps(&r.org_x, _mm_setr_ps(segment.org.x, segment.org.y, segment.org.z, segment.tnear));
    _mm_store_ps(&r.dir_x, _mm_setr_ps(dir.x, dir.y, dir.z, 0.0f));
    _mm_store_si128(reinterpret_cast<__m128i*>(&r.tfar),
                    _mm_setr_epi32(std::bit_cast<int>(segment.tfar), -1, 0, 0));  // mask all ones, id, flags
}

}  // namespace

struct EmbreeAccelerator::DeviceState {
    std::mutex mutex;
    RTCError code = RTC_ERROR_NONE;  // the first error since the last check
    std::string message;
    std::atomic<int64_t> bytes{0};  // memory Embree holds, from the memory monitor

    static void onError(void* user, RTCError code, const char* str) {
        if (code == RTC_ERROR_NONE) return;
        auto* self = static_cast<DeviceState*>(user);
        std::lock_guard lock(self->mutex);
        if (self->code != RTC_ERROR_NONE) return;
        self->code = code;
        self->message = str ? str : "";
    }

    // Possibly called from several of Embree's threads at once; we never cancel an
    // allocation, so every call counts (bytes > 0 allocated, < 0 freed).
    static bool onMemory(void* user, ssize_t bytes, bool /*post*/) {
        static_cast<DeviceState*>(user)->bytes.fetch_add(int64_t(bytes), std::memory_order_relaxed);
        return true;
    }
};

namespace {

// Turns an error Embree reported during `call` into an EmbreeError. Errors reach us through
// the device's error callback (which records them instead of throwing through Embree's C API)
// and through the per-thread error code, which is read and cleared here as well.
template <typename State>
void check(State& state, RTCDevice device, const char* call) {
    const RTCError threadCode = rtcGetDeviceError(device);
    RTCError code;
    std::string message;
    {
        std::lock_guard lock(state.mutex);
        code = state.code;
        message = std::move(state.message);
        state.code = RTC_ERROR_NONE;
        state.message.clear();
    }
    if (code == RTC_ERROR_NONE) code = threadCode;
    if (code == RTC_ERROR_NONE) return;
    throw EmbreeError(
        fmt::format("Embree error in {}: {}{}{}", call, errorName(code), message.empty() ? "" : ": ", message));
}

// The valid triangles as geometry kTriangleGeometry: Embree's primID i is our valid triangle i.
template <typename State>
void attachTriangles(State& state, RTCDevice device, RTCScene scene, RTCBuildQuality quality, const PrimitiveSet& prims,
                     std::span<const uint32_t> validTriangles) {
    const size_t count = validTriangles.size();
    std::unique_ptr<RTCGeometryTy, GeometryDeleter> geometry(rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE));
    check(state, device, "rtcNewGeometry");
    // Only used when the scene quality is low (two-level structure); a hint otherwise.
    rtcSetGeometryBuildQuality(geometry.get(), quality);
    // Embree-allocated buffers: Embree over-allocates the vertex buffer so that its last
    // element can be read with a 16-byte load (the padding rule shared buffers must obey).
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_VERTEX, 0,
                                                                 RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * count));
    check(state, device, "rtcSetNewGeometryBuffer(vertex)");
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_INDEX, 0,
                                                                   RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), count));
    check(state, device, "rtcSetNewGeometryBuffer(index)");
    // Its vertices are copied in order, so Embree's u, v are the weights of v1 and v2 as in our
    // Hit convention.
    for (size_t i = 0; i < count; ++i) {
        std::memcpy(vertices + 9 * i, &prims.triangles[validTriangles[i]], sizeof(Triangle));
        indices[3 * i + 0] = uint32_t(3 * i + 0);
        indices[3 * i + 1] = uint32_t(3 * i + 1);
        indices[3 * i + 2] = uint32_t(3 * i + 2);
    }
    rtcCommitGeometry(geometry.get());
    check(state, device, "rtcCommitGeometry");
    rtcAttachGeometryByID(scene, geometry.get(), kTriangleGeometry);  // the scene holds a reference
    check(state, device, "rtcAttachGeometry");
}

// Spheres (x y z radius each) as geometry kSphereGeometry, Embree's own point spheres.
template <typename State>
void attachSpheres(State& state, RTCDevice device, RTCScene scene, RTCBuildQuality quality,
                   const std::vector<float>& spheres) {
    std::unique_ptr<RTCGeometryTy, GeometryDeleter> geometry(rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT));
    check(state, device, "rtcNewGeometry(sphere)");
    rtcSetGeometryBuildQuality(geometry.get(), quality);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), spheres.size() / 4));
    check(state, device, "rtcSetNewGeometryBuffer(sphere)");
    std::copy(spheres.begin(), spheres.end(), vertices);
    rtcCommitGeometry(geometry.get());
    rtcAttachGeometryByID(scene, geometry.get(), kSphereGeometry);
    check(state, device, "rtcAttachGeometry(sphere)");
}

// Cones as geometry kConeGeometry, user primitives tested by ConeGeometry; `cones` must outlive
// the scene (Embree keeps a pointer to them).
template <typename State>
void attachCones(State& state, RTCDevice device, RTCScene scene, RTCBuildQuality quality, std::vector<Cone>& cones) {
    std::unique_ptr<RTCGeometryTy, GeometryDeleter> geometry(rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER));
    check(state, device, "rtcNewGeometry(user)");
    rtcSetGeometryBuildQuality(geometry.get(), quality);
    rtcSetGeometryUserPrimitiveCount(geometry.get(), unsigned(cones.size()));
    rtcSetGeometryUserData(geometry.get(), cones.data());
    rtcSetGeometryBoundsFunction(geometry.get(), &ConeGeometry::bounds, nullptr);
    rtcSetGeometryIntersectFunction(geometry.get(), &ConeGeometry::intersect);
    rtcSetGeometryOccludedFunction(geometry.get(), &ConeGeometry::occluded);
    rtcCommitGeometry(geometry.get());
    rtcAttachGeometryByID(scene, geometry.get(), kConeGeometry);
    check(state, device, "rtcAttachGeometry(user)");
}

}  // namespace

void EmbreeAccelerator::DeviceDeleter::operator()(RTCDeviceTy* device) const { rtcReleaseDevice(device); }
void EmbreeAccelerator::SceneDeleter::operator()(RTCSceneTy* scene) const { rtcReleaseScene(scene); }

EmbreeAccelerator::EmbreeAccelerator(const EmbreeConfig& config)
    : config_(config), state_(std::make_unique<DeviceState>()) {
    if (config_.threads < 0) throw EmbreeError(fmt::format("Embree: negative thread count {}", config_.threads));
    deviceConfig_ = fmt::format("threads={}", config_.threads);
    // max_isa, not isa: Embree then takes the best of its kernels up to that ISA the CPU runs,
    // where isa= would refuse an ISA the CPU lacks.
    if (!config_.maxIsa.empty()) deviceConfig_ += fmt::format(",max_isa={}", config_.maxIsa);
    RTCDevice device = rtcNewDevice(deviceConfig_.c_str());
    if (!device) {
        const RTCError code = rtcGetDeviceError(nullptr);
        throw EmbreeError(fmt::format("Embree error in rtcNewDevice(\"{}\"): {}", deviceConfig_, errorName(code)));
    }
    device_.reset(device);
    rtcSetDeviceErrorFunction(device, &DeviceState::onError, state_.get());
    rtcSetDeviceMemoryMonitorFunction(device, &DeviceState::onMemory, state_.get());
    check(*state_, device, "rtcSetDeviceErrorFunction");
}

EmbreeAccelerator::~EmbreeAccelerator() = default;

void EmbreeAccelerator::build(const PrimitiveSet& prims) {
    RTCDevice device = device_.get();
    const std::span<const uint32_t> validTriangles = prims.validTriangles();
    const size_t count = validTriangles.size();
    if (count > kMaxPrimitives)
        throw EmbreeError(
            fmt::format("Embree: {} primitives exceed the {} this binding can index", count, kMaxPrimitives));

    // Drop the previous structure first: a failed build leaves an empty (always missing) one.
    scene_.reset();
    built_ = prims;
    primitives_ = prims.valid.size();
    bytes_.reset();
    for (auto& map : primitiveOf_) map = {};
    primitiveOf_[kTriangleGeometry].table.assign(validTriangles.begin(), validTriangles.end());
    cones_.clear();
    std::vector<float> spheres;  // x y z radius per sphere
    for (uint32_t prim : prims.validQuadrics()) {
        if (prims.kind(prim) == PrimitiveKind::Sphere) {
            const Sphere& s = prims.spheres[prim - prims.sphereBase()];
            // NFF's negative radius marks an inside-visible sphere; the surface is |radius|'s.
            spheres.insert(spheres.end(), {s.centre.x, s.centre.y, s.centre.z, std::abs(s.radius)});
            primitiveOf_[kSphereGeometry].table.push_back(prim);
        } else {
            cones_.push_back(prims.cones[prim - prims.coneBase()]);
            primitiveOf_[kConeGeometry].table.push_back(prim);
        }
    }
    for (auto& map : primitiveOf_) map.compact();
    const RTCBuildQuality quality = geometryQuality(config_.quality);

    std::unique_ptr<RTCSceneTy, SceneDeleter> scene(rtcNewScene(device));
    check(*state_, device, "rtcNewScene");
    // Refit: RTC_SCENE_FLAG_DYNAMIC too, without which Embree 3.13.5 builds the geometries again at
    // every commit (an update took as long as the build on conference: 140 ms against 15).
    rtcSetSceneFlags(scene.get(), RTCSceneFlags((config_.robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE) |
                                                (config_.quality == EmbreeQuality::Refit ? RTC_SCENE_FLAG_DYNAMIC
                                                                                         : RTC_SCENE_FLAG_NONE)));
    rtcSetSceneBuildQuality(scene.get(), sceneQuality(config_.quality));
    check(*state_, device, "rtcSetSceneFlags/rtcSetSceneBuildQuality");

    // With no valid primitive the scene stays without geometry: committing an empty scene is
    // fine and every query then misses.
    if (count > 0) attachTriangles(*state_, device, scene.get(), quality, prims, validTriangles);
    if (!spheres.empty()) attachSpheres(*state_, device, scene.get(), quality, spheres);
    if (!cones_.empty()) attachCones(*state_, device, scene.get(), quality, cones_);
    const int64_t bytesBefore = state_->bytes.load();
    // Embree silently skips primitives with a coordinate beyond 1.844e18 (finite ones of
    // ours included); rays can then pass through them.
    rtcCommitScene(scene.get());
    check(*state_, device, "rtcCommitScene");
    const int64_t bytesAfter = state_->bytes.load();
    scene_ = std::move(scene);
    // What Embree's memory monitor saw rtcCommitScene keep (allocated minus freed): BVH nodes
    // and Embree's own copies of the triangles in its leaves, in whole allocator blocks; not
    // our vertex and index buffers, which only copy the input.
    if (bytesAfter > bytesBefore) bytes_ = size_t(bytesAfter - bytesBefore);
}

namespace {

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

bool EmbreeAccelerator::update(const PrimitiveSet& prims) {
    if (config_.quality != EmbreeQuality::Refit) return false;
    if (!scene_ || prims.triangles.size() != built_.triangles.size() || prims.spheres.size() != built_.spheres.size() ||
        prims.cones.size() != built_.cones.size() || prims.valid.size() != built_.valid.size())
        throw std::invalid_argument(fmt::format("embree: an update over {} valid primitives; built over {}",
                                                prims.valid.size(), scene_ ? built_.valid.size() : 0));
    built_ = prims;
    RTCDevice device = device_.get();
    const std::span<const uint32_t> validTriangles = prims.validTriangles();
    if (!validTriangles.empty())
        rewriteVertices(scene_.get(), kTriangleGeometry, [&](float* vertices) {
            for (size_t i = 0; i < validTriangles.size(); ++i)
                std::memcpy(vertices + 9 * i, &prims.triangles[validTriangles[i]], sizeof(Triangle));
        });
    const std::span<const uint32_t> quadrics = prims.validQuadrics();
    const size_t sphereCount = quadrics.size() - cones_.size();
    if (sphereCount > 0)
        rewriteVertices(scene_.get(), kSphereGeometry, [&](float* vertices) {
            for (size_t i = 0; i < sphereCount; ++i) {
                const Sphere& s = prims.spheres[quadrics[i] - prims.sphereBase()];
                const float values[4] = {s.centre.x, s.centre.y, s.centre.z, std::abs(s.radius)};
                std::memcpy(vertices + 4 * i, values, sizeof(values));
            }
        });
    for (size_t k = 0; k < cones_.size(); ++k) cones_[k] = prims.cones[quadrics[sphereCount + k] - prims.coneBase()];
    if (!cones_.empty()) rtcCommitGeometry(rtcGetGeometry(scene_.get(), kConeGeometry));  // bounds asked again
    check(*state_, device, "rtcUpdateGeometryBuffer/rtcCommitGeometry");
    rtcCommitScene(scene_.get());
    check(*state_, device, "rtcCommitScene");
    return true;
}

BuildStats EmbreeAccelerator::buildStats() const {
    // nodes, leaves, depth, SAH: Embree's tree is not visible.
    BuildStats stats;
    stats.primitives = primitives_;
    stats.bytes = bytes_;
    stats.figures.push_back({"kernel_bits", double(kernelBits()),
                             fmt::format("vector width of Embree's kernels on this device, its widest native ray "
                                         "packet (Embree::isa={})",
                                         config_.maxIsa.empty() ? "auto" : config_.maxIsa)});
    return stats;
}

int EmbreeAccelerator::kernelBits() const {
    // Embree names no ISA it chose; its packets follow the ISA (8 rays from AVX on, 16 with
    // AVX-512), so the widest one it traces natively is the width of its kernels.
    RTCDevice device = device_.get();
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) return 512;
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) return 256;
    return 128;
}

namespace {

// A ray Embree takes as it is: valid (Ray::isValid) and one segment from its origin in
// segmentsOf's terms (tmin >= 0, every coordinate within kEmbreeLarge). Tested four lanes at a
// time and joined by & rather than &&, so that a query branches once on all of it; NaN fails
// every comparison but !=, and fails `within` before that.
inline bool takenAsIs(const Ray& r) {
    static_assert(sizeof(Ray) == 32 && offsetof(Ray, dir) == 12 && offsetof(Ray, tmin) == 24 &&
                  offsetof(Ray, tmax) == 28);
    const __m128 a = _mm_loadu_ps(&r.org.x);  // org x y z, dir x
    const __m128 b = _mm_loadu_ps(&r.dir.y);  // dir y z, tmin, tmax
    const __m128 sign = _mm_set1_ps(-0.0f), large = _mm_set1_ps(kEmbreeLarge), zero = _mm_setzero_ps();
    const int withinA = _mm_movemask_ps(_mm_cmple_ps(_mm_andnot_ps(sign, a), large));
    const int withinB = _mm_movemask_ps(_mm_cmple_ps(_mm_andnot_ps(sign, b), large));
    const int nonzero =
        (_mm_movemask_ps(_mm_cmpneq_ps(a, zero)) & 0b1000) | (_mm_movemask_ps(_mm_cmpneq_ps(b, zero)) & 0b11);
    return (withinA == 0b1111) & ((withinB & 0b11) == 0b11) & (nonzero != 0) & (r.tmin >= 0.0f) & (r.tmin <= r.tmax);
}

// A ray taken as it is, in Embree's form, with the hit Embree is to fill marked empty.
inline void toRtc(const Ray& ray, RTCRayHit& r) {
    toRtc(Segment{ray.org, ray.tmin, ray.tmax, 0.0f}, ray.dir, r.ray);
    r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    r.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

// Our hit from Embree's, on our `primitive`; u, v are barycentrics on a triangle only (our Hit
// convention). `shift` is added to Embree's t (Segment::shift).
inline Hit hitOf(const RTCRayHit& r, uint32_t primitive, float shift = 0.0f) {
    const bool triangle = r.hit.geomID == kTriangleGeometry;
    return {r.ray.tfar + shift, primitive, triangle ? r.hit.u : 0.0f, triangle ? r.hit.v : 0.0f};
}

constexpr float kOccludedMark = -std::numeric_limits<float>::infinity();  // Embree's tfar of an occluded ray

}  // namespace

void EmbreeAccelerator::PrimitiveMap::compact() {
    for (size_t i = 0; i < table.size(); ++i)
        if (table[i] != table[0] + i) return;
    offset = table.empty() ? 0 : table[0];
    table = {};
}

// Interval semantics. Ours is the closed [tmin, tmax]. Embree's documentation promises
// nothing for hits exactly at or very close to tnear or tfar, and 3.13.5 answers differently
// there with its AVX2 and AVX-512 kernels (docs/accuracy.md, "Embree at the ends of the
// interval"): a hit at exactly t == tmin, which we report, Embree may miss. We pass the
// interval unchanged rather than nudge tnear: an ulp would not make its comparison exact
// either. Negative tmin: see segmentsOf above.
//
// The queries are what every caller pays on top of Embree's own call (`bvhlab bench`'s embree
// rows against embree-bare), so a ray Embree takes as it is goes straight to it: one branch on
// the checks, the conversion, the call, the index map. The rest takes the path in parts.
bool EmbreeAccelerator::findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const {
    ++counters.queries;
    if (!(takenAsIs(ray) & bool(scene_))) [[unlikely]]
        return scene_ && findNearestInParts(ray, hit);
    RTCRayHit rayhit;
    toRtc(ray, rayhit);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(scene_.get(), &context, &rayhit);
    if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit = hitOf(rayhit, primitiveOf_[rayhit.hit.geomID](rayhit.hit.primID));
    return true;
}

bool EmbreeAccelerator::isOccluded(const Ray& ray, QueryCounters& counters) const {
    ++counters.queries;
    if (!(takenAsIs(ray) & bool(scene_))) [[unlikely]]
        return scene_ && isOccludedInParts(ray);
    RTCRay r;
    toRtc(Segment{ray.org, ray.tmin, ray.tmax, 0.0f}, ray.dir, r);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded1(scene_.get(), &context, &r);
    return r.tfar == kOccludedMark;
}

bool EmbreeAccelerator::findNearestInParts(const Ray& ray, Hit& hit) const {
    if (!ray.isValid()) return false;
    const Segments segments = segmentsOf(ray);
    for (int i = 0; i < segments.count; ++i) {
        RTCRayHit rayhit;
        toRtc(segments.part[i], ray.dir, rayhit.ray);
        rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        rtcIntersect1(scene_.get(), &context, &rayhit);
        if (rayhit.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
            hit = hitOf(rayhit, primitiveOf_[rayhit.hit.geomID](rayhit.hit.primID), segments.part[i].shift);
            return true;
        }
    }
    return false;
}

bool EmbreeAccelerator::isOccludedInParts(const Ray& ray) const {
    if (!ray.isValid()) return false;
    const Segments segments = segmentsOf(ray);
    for (int i = 0; i < segments.count; ++i) {
        RTCRay r;
        toRtc(segments.part[i], ray.dir, r);
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        rtcOccluded1(scene_.get(), &context, &r);
        if (r.tfar == kOccludedMark) return true;
    }
    return false;
}

namespace {

// Rays converted per stream call: on the stack, so a batch allocates nothing.
constexpr size_t kStreamChunk = 256;

// Streams `rays` to Embree a chunk at a time: a ray Embree cannot take as it is goes to
// single(i), the single-ray call, which counts it; the others are converted by
// convert(ray, rtcRay), traced by trace(context, chunk, n) and answered by answer(i, rtcRay),
// each answer written once. The batch's coherence hint becomes the context's flag.
template <typename RtcRay, typename Single, typename Convert, typename Trace, typename Answer>
void streamInChunks(bool haveScene, View<const Ray> rays, RayCoherence coherence, QueryCounters& counters,
                    Single&& single, Convert&& convert, Trace&& trace, Answer&& answer) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = coherence == RayCoherence::Coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                                                        : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    RtcRay chunk[kStreamChunk];
    size_t index[kStreamChunk];
    for (size_t next = 0; next < rays.size();) {
        size_t n = 0;
        for (; next < rays.size() && n < kStreamChunk; ++next) {
            if (!(takenAsIs(rays[next]) & haveScene)) [[unlikely]] {
                single(next);
                continue;
            }
            convert(rays[next], chunk[n]);
            index[n++] = next;
        }
        if (n == 0) continue;
        counters.queries += n;
        trace(&context, chunk, n);
        for (size_t k = 0; k < n; ++k) answer(index[k], chunk[k]);
    }
}

}  // namespace

void EmbreeAccelerator::findNearestBatch(View<const Ray> rays, View<Hit> hits, QueryCounters& counters,
                                         View<RayCost> costs, RayCoherence coherence) const {
    std::fill(costs.begin(), costs.end(), RayCost{});
    streamInChunks<RTCRayHit>(
        bool(scene_), rays, coherence, counters,
        [&](size_t i) {
            Hit hit;
            findNearest(rays[i], hit, counters);
            hits[i] = hit;
        },
        [](const Ray& ray, RTCRayHit& rtc) { toRtc(ray, rtc); },
        [&](RTCIntersectContext* context, RTCRayHit* chunk, size_t n) {
            rtcIntersect1M(scene_.get(), context, chunk, unsigned(n), sizeof(RTCRayHit));
        },
        [&](size_t i, const RTCRayHit& rtc) {
            const RTCHit& h = rtc.hit;
            hits[i] = h.geomID == RTC_INVALID_GEOMETRY_ID ? Hit{} : hitOf(rtc, primitiveOf_[h.geomID](h.primID));
        });
}

void EmbreeAccelerator::isOccludedBatch(View<const Ray> rays, View<uint8_t> occluded, QueryCounters& counters,
                                        View<RayCost> costs, RayCoherence coherence) const {
    std::fill(costs.begin(), costs.end(), RayCost{});
    streamInChunks<RTCRay>(
        bool(scene_), rays, coherence, counters, [&](size_t i) { occluded[i] = isOccluded(rays[i], counters) ? 1 : 0; },
        [](const Ray& ray, RTCRay& rtc) {
            toRtc(Segment{ray.org, ray.tmin, ray.tmax, 0.0f}, ray.dir, rtc);
        },
        [&](RTCIntersectContext* context, RTCRay* chunk, size_t n) {
            rtcOccluded1M(scene_.get(), context, chunk, unsigned(n), sizeof(RTCRay));
        },
        [&](size_t i, const RTCRay& rtc) { occluded[i] = rtc.tfar == kOccludedMark ? 1 : 0; });
}

namespace {

// Embree as its users call it: the rays converted once (prepare and reset are not timed), then
// its calls over them with one context per range, no checks and no mapping of the answer back
// to our primitives. Single: one rtcIntersect1 / rtcOccluded1 per ray (the bench's
// embree-bare); Stream: one rtcIntersect1M / rtcOccluded1M per range. rtcOccluded needs an
// RTCRay, which an RTCRayHit starts with, so one array serves both queries.
class EmbreeRayArray final : public EmbreePreparedRays {
public:
    EmbreeRayArray(RTCScene scene, std::vector<RTCRayHit> prepared, bool stream, bool coherent)
        : scene_(scene), prepared_(std::move(prepared)), rays_(prepared_), stream_(stream), coherent_(coherent) {}

    size_t size() const override { return rays_.size(); }
    void reset() override { std::copy(prepared_.begin(), prepared_.end(), rays_.begin()); }

    size_t trace(size_t begin, size_t end, bool anyHit) override {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        if (coherent_) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        size_t hits = 0;  // Embree's answers are read, as any caller reads them
        if (!stream_) {
            for (size_t i = begin; i < end; ++i) {
                if (anyHit)
                    rtcOccluded1(scene_, &context, &rays_[i].ray);
                else
                    rtcIntersect1(scene_, &context, &rays_[i]);
                hits += hit(i);
            }
            return hits;
        }
        if (end == begin) return 0;
        if (anyHit)
            rtcOccluded1M(scene_, &context, &rays_[begin].ray, unsigned(end - begin), sizeof(RTCRayHit));
        else
            rtcIntersect1M(scene_, &context, &rays_[begin], unsigned(end - begin), sizeof(RTCRayHit));
        for (size_t i = begin; i < end; ++i) hits += hit(i);
        return hits;
    }

    size_t packetWidth() const override { return 1; }
    bool hit(size_t i) const override {
        return rays_[i].ray.tfar == kOccludedMark || rays_[i].hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    float t(size_t i) const override { return rays_[i].ray.tfar; }

private:
    RTCScene scene_;
    std::vector<RTCRayHit> prepared_;
    std::vector<RTCRayHit> rays_;
    bool stream_, coherent_;
};

// Embree's packet calls for W = 8 and 16 lanes.
template <int W>
struct PacketApi;
template <>
struct PacketApi<8> {
    using RayHit = RTCRayHit8;
    static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) {
        rtcIntersect8(valid, s, c, r);
    }
    static void occluded(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) {
        rtcOccluded8(valid, s, c, &r->ray);
    }
};
template <>
struct PacketApi<16> {
    using RayHit = RTCRayHit16;
    static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) {
        rtcIntersect16(valid, s, c, r);
    }
    static void occluded(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) {
        rtcOccluded16(valid, s, c, &r->ray);
    }
};

// The rays as SoA packets of W consecutive rays, one packet call each. The last packet's lanes
// beyond the rays repeat its first ray and are masked off (its own valid mask).
template <int W>
class EmbreeRayPackets final : public EmbreePreparedRays {
    using Api = PacketApi<W>;
    using Packet = typename Api::RayHit;

public:
    EmbreeRayPackets(RTCScene scene, const std::vector<RTCRayHit>& rays, bool coherent)
        : scene_(scene), size_(rays.size()), coherent_(coherent) {
        prepared_.resize((size_ + W - 1) / W);
        for (size_t p = 0; p < prepared_.size(); ++p)
            for (int lane = 0; lane < W; ++lane) {
                const size_t i = p * W + lane;
                setLane(prepared_[p], lane, rays[i < size_ ? i : p * W]);
            }
        packets_ = prepared_;
        const size_t inLast = size_ - (prepared_.empty() ? 0 : (prepared_.size() - 1) * W);
        for (int lane = 0; lane < W; ++lane) {
            all_.lanes[lane] = -1;
            last_.lanes[lane] = size_t(lane) < inLast ? -1 : 0;
        }
    }

    size_t size() const override { return size_; }
    void reset() override { std::copy(prepared_.begin(), prepared_.end(), packets_.begin()); }

    size_t trace(size_t begin, size_t end, bool anyHit) override {
        if (begin % W != 0)
            throw std::logic_error(
                fmt::format("Embree's {}-ray packets: a range must start at a multiple of {}, not {}", W, W, begin));
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        if (coherent_) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        const size_t last = prepared_.size() - 1;
        for (size_t p = begin / W; p * W < end; ++p) {
            const int* valid = p == last ? last_.lanes : all_.lanes;
            if (anyHit)
                Api::occluded(valid, scene_, &context, &packets_[p]);
            else
                Api::intersect(valid, scene_, &context, &packets_[p]);
        }
        size_t hits = 0;
        for (size_t i = begin; i < end; ++i) hits += hit(i);
        return hits;
    }

    size_t packetWidth() const override { return W; }
    bool hit(size_t i) const override {
        const Packet& p = packets_[i / W];
        return p.ray.tfar[i % W] == kOccludedMark || p.hit.geomID[i % W] != RTC_INVALID_GEOMETRY_ID;
    }
    float t(size_t i) const override { return packets_[i / W].ray.tfar[i % W]; }

private:
    // An RTCRay is twelve 4-byte fields in the order of the packet's arrays of W (RTCRayN).
    static void setLane(Packet& p, int lane, const RTCRayHit& r) {
        static_assert(sizeof(RTCRay) == 12 * 4 && sizeof(p.ray) == 12 * 4 * W);
        for (int field = 0; field < 12; ++field)
            std::memcpy(reinterpret_cast<char*>(&p.ray) + 4 * (field * W + lane),
                        reinterpret_cast<const char*>(&r.ray) + 4 * field, 4);
        rtcCopyHitToHitN(reinterpret_cast<RTCHitN*>(&p.hit), &r.hit, W, unsigned(lane));
    }

    struct alignas(4 * W) Mask {  // Embree reads a packet's valid mask with one aligned load
        int lanes[W];
    };

    RTCScene scene_;
    size_t size_;
    bool coherent_;
    std::vector<Packet> prepared_, packets_;  // Packet is aligned as Embree requires
    Mask all_, last_;
};

}  // namespace

std::vector<std::string> EmbreeAccelerator::batchApis() const {
    std::vector<std::string> apis = {"stream"};
    if (rtcGetDeviceProperty(device_.get(), RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) apis.push_back("packet8");
    if (rtcGetDeviceProperty(device_.get(), RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) apis.push_back("packet16");
    return apis;
}

// A user of Embree hands it rays it accepts; the two-segment form of findNearest for a negative
// tmin is ours, so such a ray (or one Embree would assert on) is refused, not traced differently.
std::unique_ptr<EmbreePreparedRays> EmbreeAccelerator::prepareRays(const std::vector<Ray>& rays, std::string_view api,
                                                                   bool coherent) const {
    if (!scene_) throw std::logic_error("EmbreeAccelerator::prepareRays before build()");
    const std::vector<std::string> batch = batchApis();
    if (api != "single" && std::find(batch.begin(), batch.end(), api) == batch.end())
        throw std::invalid_argument(
            fmt::format("Embree's ray API '{}': not single or one of this machine's {}", api, fmt::join(batch, ", ")));
    std::vector<RTCRayHit> prepared(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
        if (!takenAsIs(rays[i]))
            throw std::invalid_argument(fmt::format(
                "Embree's {} API: ray {} (tmin {}, tmax {}) is not one Embree takes as it is: a valid interval "
                "with tmin >= 0 and coordinates within +-{}",
                api, i, rays[i].tmin, rays[i].tmax, kEmbreeLarge));
        toRtc(rays[i], prepared[i]);
    }
    if (api == "packet8") return std::make_unique<EmbreeRayPackets<8>>(scene_.get(), prepared, coherent);
    if (api == "packet16") return std::make_unique<EmbreeRayPackets<16>>(scene_.get(), prepared, coherent);
    return std::make_unique<EmbreeRayArray>(scene_.get(), std::move(prepared), api == "stream", coherent);
}

std::unique_ptr<NativeRayBatch> EmbreeAccelerator::prepareNativeBatch(const std::vector<Ray>& rays) const {
    return prepareRays(rays, "single", false);
}

}  // namespace bvhlab
