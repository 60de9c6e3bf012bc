// Rays in an accelerator's own format, made once outside any timing and answered by its own
// call in a bare loop: what a user of its native API writes (Embree: an array of RTCRayHit and
// a loop of rtcIntersect1). The yardstick of `bvhlab bench`'s single rows (its embree-bare row);
// what the interface's per-ray conversion and checks cost is the wrapped row's ratio to it.
#pragma once

#include <bvhlab/ray.h>

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

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

// The native APIs of an outside library (Embree: its single-ray call, its stream, and packets of 8
// or 16 rays), which its wrapper implements beside Accelerator; `bvhlab bench` finds them with
// dynamic_cast and keeps them as the yardsticks of its rows (embree-bare, embree-batch). Not part
// of Accelerator, which is the plugin API: a plugin's accelerator cannot offer them.
class NativeBatchApis {
public:
    virtual ~NativeBatchApis() = default;

    // The rays in the library's own format, for a bare loop of its single-ray call after build().
    // Throws std::invalid_argument naming the first ray the native call cannot take as it is.
    virtual std::unique_ptr<NativeRayBatch> prepareNativeBatch(const std::vector<Ray>& rays) const = 0;

    // The APIs' names, e.g. "stream", "packet8", "packet16": those this machine runs natively.
    virtual std::vector<std::string> batchApis() const = 0;

    // The rays prepared for `api` (one of batchApis(), else std::invalid_argument), after
    // build(); refused as prepareNativeBatch refuses them. `coherence`: the hint the batch calls
    // take (RayCoherence), passed to the API where it takes one. A packet API traces whole
    // packets: trace()'s ranges must start at multiples of 16.
    virtual std::unique_ptr<NativeRayBatch> prepareBatchApi(const std::vector<Ray>& rays, std::string_view api,
                                                            RayCoherence coherence) const = 0;
};

}  // namespace bvhlab
