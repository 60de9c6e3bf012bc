// Our rays in Embree's terms, and our queries on an Embree scene, for bvhlab's Embree structures
// (EmbreeAccelerator, EmbreeInstances): which rays Embree takes as they are, their conversion,
// Embree's answers read back, the rays it cannot take traced in parts, and batches through its
// stream API. Internal to accel/embree: it includes Embree's headers.
#pragma once

#include "accel/embree/embree_scene.h"

#include <bvhlab/counters.h>
#include <bvhlab/ray.h>
#include <bvhlab/view.h>

#include <embree3/rtcore.h>
#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <limits>

namespace bvhlab::embree {

// Largest coordinate Embree accepts in a ray (its FLT_LARGE). Debian's libembree3 is built
// with assertions enabled, and rtcIntersect1/rtcOccluded1 assert ray.valid() (|org|, |dir|
// components <= 1.844e18, so no infinities) and tnear >= 0: a ray breaking either aborts the
// process. Such rays never reach Embree.
inline constexpr float kLarge = 1.844E18f;

constexpr float kOccludedMark = -std::numeric_limits<float>::infinity();  // Embree's tfar of an occluded ray

inline bool withinRange(const Vec3& v) {
    return std::abs(v.x) <= kLarge && std::abs(v.y) <= kLarge && std::abs(v.z) <= kLarge;
}

// A ray in Embree's terms: one or two segments, each with tnear >= 0, in order of increasing t.
// Embree requires tnear >= 0 (besides the assertion, its traversal clamps the box interval at
// 0 while the triangle test uses tnear as given). A ray whose interval starts behind its
// origin is therefore traced in two parts: first [tmin, min(tmax, 0)] from the moved origin
// org + tmin*dir (tnear 0, and tmin added back to the hit distance), then, if nothing was
// found there, [0, tmax] from the original origin. Hits at t >= 0 are thus exactly as for a
// ray with tmin = 0; hits behind the origin carry the rounding of the moved origin and of the
// sum (absolute error about an ulp of |tmin|). The backward part is skipped when tmin = -inf
// (it cannot be moved to) or when the moved origin is beyond kLarge: hits behind the origin
// are then not reported. A ray with a direction component beyond kLarge (or infinite), or an
// origin that is, has no segments: it misses without reaching Embree.
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
    if (!withinRange(ray.dir)) return s;
    if (ray.tmin >= 0.0f) {
        if (withinRange(ray.org)) s.part[s.count++] = {ray.org, ray.tmin, ray.tmax, 0.0f};
        return s;
    }
    if (std::isfinite(ray.tmin)) {
        const Vec3 moved = ray.org + ray.tmin * ray.dir;
        if (withinRange(moved)) s.part[s.count++] = {moved, 0.0f, std::min(ray.tmax, 0.0f) - ray.tmin, ray.tmin};
    }
    if (ray.tmax >= 0.0f && withinRange(ray.org)) s.part[s.count++] = {ray.org, 0.0f, ray.tmax, 0.0f};
    return s;
}

// A ray Embree takes as it is: valid (Ray::isValid) and one segment from its origin in
// segmentsOf's terms (tmin >= 0, every coordinate within kLarge). Tested four lanes at a
// time and joined by & rather than &&, so that a query branches once on all of it; NaN fails
// every comparison but !=, and fails `within` before that.
inline bool takenAsIs(const Ray& r) {
    static_assert(sizeof(Ray) == 32 && offsetof(Ray, dir) == 12 && offsetof(Ray, tmin) == 24 &&
                  offsetof(Ray, tmax) == 28);
    const __m128 a = _mm_loadu_ps(&r.org.x);  // org x y z, dir x
    const __m128 b = _mm_loadu_ps(&r.dir.y);  // dir y z, tmin, tmax
    const __m128 sign = _mm_set1_ps(-0.0f), large = _mm_set1_ps(kLarge), zero = _mm_setzero_ps();
    const int withinA = _mm_movemask_ps(_mm_cmple_ps(_mm_andnot_ps(sign, a), large));
    const int withinB = _mm_movemask_ps(_mm_cmple_ps(_mm_andnot_ps(sign, b), large));
    const int nonzero =
        (_mm_movemask_ps(_mm_cmpneq_ps(a, zero)) & 0b1000) | (_mm_movemask_ps(_mm_cmpneq_ps(b, zero)) & 0b11);
    return (withinA == 0b1111) & ((withinB & 0b11) == 0b11) & (nonzero != 0) & (r.tmin >= 0.0f) & (r.tmin <= r.tmax);
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

// A ray taken as it is, in Embree's form for an any-hit query.
inline void toRtc(const Ray& ray, RTCRay& r) { toRtc(Segment{ray.org, ray.tmin, ray.tmax, 0.0f}, ray.dir, r); }

// A ray taken as it is, in Embree's form, with the hit Embree is to fill marked empty.
inline void toRtc(const Ray& ray, RTCRayHit& r) {
    toRtc(ray, r.ray);
    r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    r.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

// Our hit from Embree's, on our `primitive`; u, v are barycentrics on a triangle only (our Hit
// convention).
inline Hit hitOf(const RTCRayHit& r, uint32_t primitive) {
    const bool triangle = r.hit.geomID == kEmbreeTriangleGeometry;
    return {r.ray.tfar, primitive, triangle ? r.hit.u : 0.0f, triangle ? r.hit.v : 0.0f};
}

// The queries of a ray Embree cannot take as it is, segment by segment (segmentsOf) on
// `scene`. intersectInParts leaves in `rayhit` the answering segment's hit, its tfar our t.
bool intersectInParts(RTCScene scene, const Ray& ray, RTCRayHit& rayhit);
bool occludedInParts(RTCScene scene, const Ray& ray);

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

// Interval semantics. Ours is the closed [tmin, tmax]. Embree's documentation promises
// nothing for hits exactly at or very close to tnear or tfar, and 3.13.5 answers differently
// there with its AVX2 and AVX-512 kernels (docs/accuracy.md, "Embree at the ends of the
// interval"): a hit at exactly t == tmin, which we report, Embree may miss. We pass the
// interval unchanged rather than nudge tnear: an ulp would not make its comparison exact
// either. Negative tmin: see segmentsOf.
//
// The queries on `scene` (null before a build: every ray misses), each counting one query. They
// are what every caller pays on top of Embree's own call (`bvhlab bench`'s embree rows against
// embree-bare), so a ray Embree takes as it is goes straight to it: one branch on the checks, the
// conversion, the call, the index map. The rest takes the path in parts. primitiveOf(RTCHit)
// names our primitive of Embree's hit.
template <typename PrimitiveOf>
inline bool findNearest(RTCScene scene, const Ray& ray, Hit& hit, QueryCounters& counters, PrimitiveOf&& primitiveOf) {
    ++counters.queries;
    RTCRayHit rayhit;
    if (!(takenAsIs(ray) & (scene != nullptr))) [[unlikely]] {
        if (!scene || !intersectInParts(scene, ray, rayhit)) return false;
    } else {
        toRtc(ray, rayhit);
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        rtcIntersect1(scene, &context, &rayhit);
        if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    }
    hit = hitOf(rayhit, primitiveOf(rayhit.hit));
    return true;
}

inline bool isOccluded(RTCScene scene, const Ray& ray, QueryCounters& counters) {
    ++counters.queries;
    if (!(takenAsIs(ray) & (scene != nullptr))) [[unlikely]]
        return scene && occludedInParts(scene, ray);
    RTCRay r;
    toRtc(ray, r);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded1(scene, &context, &r);
    return r.tfar == kOccludedMark;
}

// The batches through Embree's stream API (rtcIntersect1M / rtcOccluded1M); `costs` are zero:
// Embree does not count.
template <typename PrimitiveOf>
void findNearestBatch(RTCScene scene, View<const Ray> rays, View<Hit> hits, QueryCounters& counters,
                      View<RayCost> costs, RayCoherence coherence, PrimitiveOf&& primitiveOf) {
    std::fill(costs.begin(), costs.end(), RayCost{});
    streamInChunks<RTCRayHit>(
        scene != nullptr, rays, coherence, counters,
        [&](size_t i) {
            Hit hit;
            findNearest(scene, rays[i], hit, counters, primitiveOf);
            hits[i] = hit;
        },
        [](const Ray& ray, RTCRayHit& rtc) { toRtc(ray, rtc); },
        [&](RTCIntersectContext* context, RTCRayHit* chunk, size_t n) {
            rtcIntersect1M(scene, context, chunk, unsigned(n), sizeof(RTCRayHit));
        },
        [&](size_t i, const RTCRayHit& rtc) {
            hits[i] = rtc.hit.geomID == RTC_INVALID_GEOMETRY_ID ? Hit{} : hitOf(rtc, primitiveOf(rtc.hit));
        });
}

inline void isOccludedBatch(RTCScene scene, View<const Ray> rays, View<uint8_t> occluded, QueryCounters& counters,
                            View<RayCost> costs, RayCoherence coherence) {
    std::fill(costs.begin(), costs.end(), RayCost{});
    streamInChunks<RTCRay>(
        scene != nullptr, rays, coherence, counters,
        [&](size_t i) { occluded[i] = isOccluded(scene, rays[i], counters) ? 1 : 0; },
        [](const Ray& ray, RTCRay& rtc) { toRtc(ray, rtc); },
        [&](RTCIntersectContext* context, RTCRay* chunk, size_t n) {
            rtcOccluded1M(scene, context, chunk, unsigned(n), sizeof(RTCRay));
        },
        [&](size_t i, const RTCRay& rtc) { occluded[i] = rtc.tfar == kOccludedMark ? 1 : 0; });
}

}  // namespace bvhlab::embree
