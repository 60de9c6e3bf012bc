#include "accel/embree/embree_accelerator.h"
#include "accel/embree/embree_rays.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace bvhlab {

using embree::kOccludedMark;
using embree::takenAsIs;
using embree::toRtc;

EmbreeAccelerator::EmbreeAccelerator(const EmbreeConfig& config) : config_(config), device_(config) {}

EmbreeAccelerator::~EmbreeAccelerator() = default;

void EmbreeAccelerator::build(const PrimitiveSet& prims) { scene_.build(device_, config_, prims); }

bool EmbreeAccelerator::update(const PrimitiveSet& prims) {
    if (config_.quality != EmbreeQuality::Refit) return false;
    scene_.update(device_, prims);
    return true;
}

BuildStats EmbreeAccelerator::buildStats() const {
    // nodes, leaves, depth, SAH: Embree's tree is not visible.
    BuildStats stats;
    stats.primitives = scene_.primitives();
    stats.bytes = scene_.bytes();
    stats.figures.push_back({"kernel_bits", double(kernelBits()),
                             fmt::format("vector width of Embree's kernels on this device, its widest native ray "
                                         "packet (Embree::isa={})",
                                         config_.maxIsa.empty() ? "auto" : config_.maxIsa)});
    return stats;
}

// The queries and their interval semantics: embree_rays.h.
bool EmbreeAccelerator::findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const {
    return embree::findNearest(scene_.get(), ray, hit, counters,
                               [this](const RTCHit& h) { return scene_.primitive(h.geomID, h.primID); });
}

bool EmbreeAccelerator::isOccluded(const Ray& ray, QueryCounters& counters) const {
    return embree::isOccluded(scene_.get(), ray, counters);
}

void EmbreeAccelerator::findNearestBatch(View<const Ray> rays, View<Hit> hits, QueryCounters& counters,
                                         View<RayCost> costs, RayCoherence coherence) const {
    embree::findNearestBatch(scene_.get(), rays, hits, counters, costs, coherence,
                             [this](const RTCHit& h) { return scene_.primitive(h.geomID, h.primID); });
}

void EmbreeAccelerator::isOccludedBatch(View<const Ray> rays, View<uint8_t> occluded, QueryCounters& counters,
                                        View<RayCost> costs, RayCoherence coherence) const {
    embree::isOccludedBatch(scene_.get(), rays, occluded, counters, costs, coherence);
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
                api, i, rays[i].tmin, rays[i].tmax, embree::kLarge));
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
