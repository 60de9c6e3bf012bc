#include "accel/embree/embree_rays.h"

namespace bvhlab::embree {

bool intersectInParts(RTCScene scene, const Ray& ray, RTCRayHit& rayhit) {
    if (!ray.isValid()) return false;
    const Segments segments = segmentsOf(ray);
    for (int i = 0; i < segments.count; ++i) {
        toRtc(segments.part[i], ray.dir, rayhit.ray);
        rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        rtcIntersect1(scene, &context, &rayhit);
        if (rayhit.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
            rayhit.ray.tfar += segments.part[i].shift;
            return true;
        }
    }
    return false;
}

bool occludedInParts(RTCScene scene, const Ray& ray) {
    if (!ray.isValid()) return false;
    const Segments segments = segmentsOf(ray);
    for (int i = 0; i < segments.count; ++i) {
        RTCRay r;
        toRtc(segments.part[i], ray.dir, r);
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        rtcOccluded1(scene, &context, &r);
        if (r.tfar == kOccludedMark) return true;
    }
    return false;
}

}  // namespace bvhlab::embree
