// The rays the conformance suite and the tests send at generated scenes, each kind aimed at a
// way a structure can go wrong. All deterministic for a given seed (VerifyRng, verify_rng.h).
#pragma once

#include "framework/core/accelerator.h"
#include "framework/scene/scene.h"

#include <cstdint>
#include <vector>

namespace bvhlab::verify {

enum class RayKind {
    Outside,       // origins outside the scene bounds, aimed at random points inside them
    Inside,        // origins inside the bounds, random directions
    EdgeAimed,     // aimed at lerp(va, vb, s) of a triangle edge, from random distances
    VertexAimed,   // aimed exactly at a vertex
    AxisParallel,  // direction exactly +-x/+-y/+-z; origins random or at vertex coordinates
    Grazing,       // direction within 1e-6..1e-1 rad of a triangle's plane (sometimes 0)
    Interval,      // very short rays (tmax tiny, hit just inside or outside), tmin > 0,
                   // tmin == tmax, negative tmin, tmin > tmax
    Invalid,       // NaN in any component, zero direction: must miss, must not crash
};
inline constexpr RayKind kAllRayKinds[] = {RayKind::Outside,     RayKind::Inside,       RayKind::EdgeAimed,
                                           RayKind::VertexAimed, RayKind::AxisParallel, RayKind::Grazing,
                                           RayKind::Interval,    RayKind::Invalid};
const char* rayKindName(RayKind kind);

// How many rays of `kind` the correctness checks send at `scene`: the generated scenes are at
// most ~10k triangles, and larger ones get fewer rays, so the oracle stays at O(1e8) tests.
size_t raysPerKind(const Scene& scene, RayKind kind);

// `bounds` is where random rays are aimed (an empty box is replaced by [-1,1]^3). Kinds that
// need triangles fall back to Outside rays when prims has no valid one.
std::vector<Ray> generateRays(RayKind kind, const PrimitiveSet& prims, const Bounds3& bounds, size_t count,
                              uint32_t seed);

// Rays from outside the scene's bounds toward random points well inside random valid
// triangles (barycentric coordinates >= 0.1), unit direction, tmin 0, tmax infinite.
std::vector<Ray> raysTowardTriangles(const Scene& scene, size_t count, uint64_t seed);

}  // namespace bvhlab::verify
