// Rays in an accelerator's own format, made once outside any timing and answered by its own
// call in a bare loop: what a user of its native API writes (Embree: an array of RTCRayHit and
// a loop of rtcIntersect1). The yardstick of `bvhlab bench` (its embree-bare row); what the
// interface's per-ray conversion and checks cost is the wrapped row's ratio to it.
#pragma once

#include <cstddef>

namespace bvhlab {

class NativeRayBatch {
public:
    virtual ~NativeRayBatch() = default;

    virtual size_t size() const = 0;

    // Restores every ray as prepared: a native query writes its answer into the ray (Embree
    // shortens tfar), so a second pass over answered rays would do less work. Not timed.
    virtual void reset() = 0;

    // Answers rays [begin, end), closest hit or any hit, and returns how many hit (which also
    // keeps the loop from being optimised away). Disjoint ranges may run concurrently.
    virtual size_t trace(size_t begin, size_t end, bool anyHit) = 0;
};

}  // namespace bvhlab
