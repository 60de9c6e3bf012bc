// Rays and hits between NumPy arrays and the framework's Ray and Hit: the arrays are checked
// (shape, dtype, length), and every problem is an InputError naming the argument.
#pragma once

#include "framework/core/accelerator.h"

#include <pybind11/numpy.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace bvhlab {

// One answer of accel.intersect: prim is -1 and t is inf on a miss. The counted kinds add the
// ray's N_IT and N_TR (counters=True) as floats, so that a structure without counters can say
// NaN ("not counted") in the same layout.
struct HitRecord {
    float t;
    int64_t prim;
    float u;
    float v;
};
struct CountedHitRecord {
    float t;
    int64_t prim;
    float u;
    float v;
    float n_it;
    float n_tr;
};
struct CountedOcclusionRecord {
    bool occluded;
    float n_it;
    float n_tr;
};

// Sets out.n_it and out.n_tr from costs[i], or to NaN when costs is empty: the structure counts
// nothing, and 0 would read as a ray that cost nothing.
template <typename CountedRecord>
void writeCounters(std::span<const RayCost> costs, size_t i, CountedRecord& out) {
    constexpr float notCounted = std::numeric_limits<float>::quiet_NaN();
    out.n_it = costs.empty() ? notCounted : float(costs[i].intersectionTests);
    out.n_tr = costs.empty() ? notCounted : float(costs[i].traversalSteps);
}

// Rays in NumPy arrays, checked once (with the GIL held) and read in place through the arrays'
// strides, range by range, without calling Python (so with the GIL released): origins and
// directions (N, 3) float32 or float64 of any strides (a column slice of a table of rays, every
// other row, Fortran order, a broadcast direction), N >= 0; tmin and tmax a number or an (N,)
// float array.
class RayArrays {
public:
    RayArrays(const pybind11::handle& origins, const pybind11::handle& directions, const pybind11::handle& tmin,
              const pybind11::handle& tmax);
    size_t size() const { return size_; }
    // Rays [begin, begin + out.size()).
    void read(size_t begin, std::span<Ray> out) const;
    std::vector<Ray> all() const;

private:
    // The values of a float32 or float64 array of one or two dimensions, or `constant` for every
    // ray. Read with memcpy: a field of a packed structured array need not be aligned.
    struct Values {
        pybind11::array array;  // keeps `data` alive
        const char* data = nullptr;
        pybind11::ssize_t rowStride = 0, columnStride = 0;  // in bytes, either may be negative or 0
        bool isDouble = false;
        float constant = 0.0f;
        float operator()(size_t row, size_t column = 0) const {
            if (!data) return constant;
            const char* value = data + pybind11::ssize_t(row) * rowStride + pybind11::ssize_t(column) * columnStride;
            if (isDouble) {
                double d;
                std::memcpy(&d, value, sizeof d);
                return float(d);
            }
            float f;
            std::memcpy(&f, value, sizeof f);
            return f;
        }
    };
    static Values valuesOf(pybind11::array array);
    static Values intervalOf(const pybind11::handle& object, const std::string& name, size_t n);

    size_t size_ = 0;
    Values origins_, directions_, tmin_, tmax_;
};

// {"origins", "directions", "tmin", "tmax"}: float32 arrays, the arguments of accel.intersect.
pybind11::dict raysToArrays(const std::vector<Ray>& rays);

// Writes hits[i] (and costs[i] for a CountedHitRecord, see writeCounters) as out[i].
template <typename Record>
void writeHitRecords(std::span<const Hit> hits, std::span<const RayCost> costs, Record* out) {
    for (size_t i = 0; i < hits.size(); ++i) {
        const Hit& h = hits[i];
        out[i].t = h.t;
        out[i].prim = h.found() ? int64_t(h.primitive) : -1;
        out[i].u = h.u;
        out[i].v = h.v;
        if constexpr (std::is_same_v<Record, CountedHitRecord>) writeCounters(costs, i, out[i]);
    }
}

// A structured array of HitRecord.
pybind11::array hitsToArray(const std::vector<Hit>& hits);

// Hits from an array with fields t, prim, u, v (prim < 0: a miss).
std::vector<Hit> hitsFromArray(const pybind11::handle& hits);

}  // namespace bvhlab
