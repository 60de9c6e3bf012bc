// Intel Embree 3 behind our interface: the speed reference. One geometry per primitive kind
// over the valid primitives (triangles; spheres as its sphere points; cones as a user geometry
// with our own test), queried with rtcIntersect1 / rtcOccluded1, batches with its stream API.
//
// Embree has no counters and no visible tree: N_IT, N_TR, the node statistics and the SAH
// cost are unavailable (hasCounters() is false, those optional BuildStats fields stay empty);
// only counters.queries is counted. BuildStats::bytes is Embree's own memory for the structure
// as its memory monitor reports it (EmbreeScene::bytes).
//
// ISA and threads: each instance owns its device (embree_device.h), so structures of different
// ISAs never share one; buildStats' figure kernel_bits says what width ran. The device's thread
// count applies process-wide: merely constructing this accelerator changes the thread count of
// everything else in the process (our builders and the renderer then run under the same limit,
// which is what makes build times comparable).
//
// Interval semantics (embree_rays.h): ours is the closed [tmin, tmax]; Embree makes no promise
// for hits exactly at (or very near) either end -- its default test excludes t == tnear -- and it
// requires tnear >= 0 (for a negative tmin we trace the part behind the origin from a moved
// origin, then the rest as usual). Rays with an infinite or huge (> 1.844e18) origin or direction
// component miss without reaching Embree, whose Debian build asserts on them.
#pragma once

#include "accel/embree/embree_device.h"
#include "accel/embree/embree_scene.h"
#include "framework/core/accelerator.h"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace bvhlab {

// Rays prepared for one of Embree's APIs, whose answers can be read after trace(): what the
// tests compare across the APIs. The APIs: "single", one rtcIntersect1 / rtcOccluded1 per ray;
// "stream", one rtcIntersect1M / rtcOccluded1M per range; "packet8" and "packet16", SoA packets
// through rtcIntersect8/16 and rtcOccluded8/16. A packet API traces whole packets, so
// trace(begin, end) needs begin to be a multiple of packetWidth() (ranges of 4096 are).
class EmbreePreparedRays : public NativeRayBatch {
public:
    virtual size_t packetWidth() const = 0;  // 1 but for packets
    // Ray i after the last trace: whether it hit (closest hit) or is occluded (any hit), and,
    // after a closest-hit trace, Embree's distance of the hit.
    virtual bool hit(size_t i) const = 0;
    virtual float t(size_t i) const = 0;
};

class EmbreeAccelerator final : public BuildStatsAccelerator, public NativeBatchApis {
public:
    // Creates the device; throws EmbreeError when Embree refuses (e.g. unsupported CPU).
    explicit EmbreeAccelerator(const EmbreeConfig& config = {});
    ~EmbreeAccelerator() override;
    EmbreeAccelerator(const EmbreeAccelerator&) = delete;
    EmbreeAccelerator& operator=(const EmbreeAccelerator&) = delete;

    const char* name() const override { return "embree"; }
    void build(const PrimitiveSet& prims) override;
    // With Embree::quality=refit, the moved vertices, spheres and cones written into the
    // geometries (rtcUpdateGeometryBuffer, rtcCommitGeometry) and the scene committed, which
    // refits each geometry's tree; at the other qualities there is no update (false).
    bool update(const PrimitiveSet& prims) override;
    BuildStats buildStats() const override;
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override;
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override;
    // Through Embree's stream API (rtcIntersect1M / rtcOccluded1M) in chunks converted on the
    // stack; a ray Embree cannot take as it is (negative tmin, coordinates beyond its range)
    // takes the single-ray path. `costs` are zero: Embree does not count.
    void findNearestBatch(View<const Ray> rays, View<Hit> hits, QueryCounters& counters, View<RayCost> costs,
                          RayCoherence coherence) const override;
    void isOccludedBatch(View<const Ray> rays, View<uint8_t> occluded, QueryCounters& counters, View<RayCost> costs,
                         RayCoherence coherence) const override;
    bool hasCounters() const override { return false; }
    // Rays with tmin >= 0 and coordinates within Embree's range, as RTCRayHit; see the .cpp.
    // The bare loop: prepareRays(rays, "single", false).
    std::unique_ptr<NativeRayBatch> prepareNativeBatch(const std::vector<Ray>& rays) const override;

    // Embree's batch APIs (bvhlab bench's embree-batch): "stream" always, and "packet8" and
    // "packet16" where the device says it traces such packets natively.
    std::vector<std::string> batchApis() const override;
    std::unique_ptr<NativeRayBatch> prepareBatchApi(const std::vector<Ray>& rays, std::string_view api,
                                                    RayCoherence coherence) const override {
        return prepareRays(rays, api, coherence == RayCoherence::Coherent);
    }
    // The rays prepared for `api`, "single" or one of batchApis() (else std::invalid_argument),
    // refused as prepareNativeBatch refuses them; `coherent` sets
    // RTC_INTERSECT_CONTEXT_FLAG_COHERENT in the context of every call (else INCOHERENT).
    std::unique_ptr<EmbreePreparedRays> prepareRays(const std::vector<Ray>& rays, std::string_view api,
                                                    bool coherent) const;

    const EmbreeConfig& config() const { return config_; }
    // The device's configuration string, e.g. "threads=1" or "threads=1,max_isa=avx2".
    const std::string& deviceConfig() const { return device_.configString(); }
    // The vector width of the kernels Embree runs on this device, in bits: 128 (SSE), 256 (AVX,
    // AVX2) or 512 (AVX-512). buildStats() reports it as the figure kernel_bits, as BVH's.
    int kernelBits() const { return device_.kernelBits(); }

private:
    EmbreeConfig config_;
    EmbreeDevice device_;
    EmbreeScene scene_;  // after device_: released before it
};

}  // namespace bvhlab
