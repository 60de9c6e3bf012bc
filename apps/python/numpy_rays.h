// Rays and hits between NumPy arrays and the framework's Ray and Hit: the arrays are checked
// (shape, dtype, contiguity, length), and every problem is an InputError naming the argument.
#pragma once

#include "framework/core/accelerator.h"

#include <pybind11/numpy.h>

#include <cstdint>
#include <vector>

namespace bvhlab {

// One answer of accel.intersect: prim is -1 and t is inf on a miss. The counted kinds add the
// ray's N_IT and N_TR (counters=True).
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
    uint32_t n_it;
    uint32_t n_tr;
};
struct CountedOcclusionRecord {
    bool occluded;
    uint32_t n_it;
    uint32_t n_tr;
};

// origins and directions (N, 3) float32 or float64, C-contiguous, N > 0; tmin and tmax a number
// or an (N,) float array.
std::vector<Ray> raysFromArrays(const pybind11::handle& origins, const pybind11::handle& directions,
                                const pybind11::handle& tmin, const pybind11::handle& tmax);

// {"origins", "directions", "tmin", "tmax"}: float32 arrays, the arguments of accel.intersect.
pybind11::dict raysToArrays(const std::vector<Ray>& rays);

// A structured array of HitRecord (or CountedHitRecord when costs is not empty).
pybind11::array hitsToArray(const std::vector<Hit>& hits, const std::vector<RayCost>& costs);

// Hits from an array with fields t, prim, u, v (prim < 0: a miss).
std::vector<Hit> hitsFromArray(const pybind11::handle& hits);

}  // namespace bvhlab
