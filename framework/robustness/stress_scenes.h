// Scenes and rays for the robustness stress suite (`bvhlab stress`, tests/framework/robustness/test_stress.cpp):
// closed meshes for the watertightness probes, the scale/translation transform, a lit plane far
// from the origin for shadow acne, and the builders' edge cases. All deterministic. The random
// triangles they are made of build the tests' generated scenes too (apps/check/oracle.cpp).
#pragma once

#include "framework/robustness/stress_rng.h"
#include "framework/scene/scene.h"

#include <functional>
#include <string>
#include <vector>

namespace bvhlab {

// A cube of n x n quads per face (2 triangles each), outward-wound and closed: points on the
// shared cube edges are computed from integer grid coordinates, so they are bit-identical on
// both faces. Axis-aligned on purpose (zero-thickness boxes, axis-parallel slabs).
void addSubdividedBox(Scene& scene, const Vec3& lower, const Vec3& upper, int n, uint32_t material);

// The generated closed meshes, each finalized and named after its parameters, placed off the
// origin: "icosphereS" (S subdivisions), "cubeN" (N x N quads per face), "torusMxN".
Scene makeIcosphereMesh(int subdivisions);
Scene makeSubdividedCubeMesh(int n);
Scene makeTorusMesh(int majorSegments, int minorSegments);
// Icosphere, cube and torus side by side, disjoint: the scene of the scale/translation sweep.
Scene makeClosedTrioScene(int icosphereSubdivisions, int cubeN, int torusMajor, int torusMinor);

// The scene with every position mapped to float(scale * p + offset) (computed in double),
// lights and camera likewise; normals and topology unchanged. Finalized.
Scene transformedScene(const Scene& scene, double scale, const DVec3& offset);

// Rays from outside the scene's bounds toward random points well inside random valid
// triangles (barycentric coordinates >= 0.1), unit direction, tmin 0, tmax infinite.
std::vector<Ray> raysTowardTriangles(const Scene& scene, size_t count, uint64_t seed);

// A square plane of cells x cells quads, `size` across, whose centre lies at `distance` from the
// origin, with a camera looking at it from above and a point light above it (both on the same
// side), so that every pixel shows the plane, lit. `tilted` = false: the plane is z = const,
// axis-aligned; true: a generic orientation. Finalized.
Scene makeDistantPlaneScene(double distance, bool tilted, int cells = 32, double size = 200.0);

// munich's ground: the plane z = 0 exactly (so a ray origin offset along its normal moves by
// the magnitude of z, which is 0), `size` across, centred `distance` from the origin in x and
// y, made of two triangles, seen from above and lit from `elevationDegrees` above the horizon.
// Finalized.
Scene makeGroundPlaneScene(double distance, double size, double elevationDegrees);

// A random triangle around `centre`: vertices centre + a, centre + b and centre - a - b for
// random a, b of length `size`, so that its centroid is `centre` (exactly in double; the float
// centroid is within rounding of it).
void addTriangleAround(Scene& scene, StressRng& rng, const DVec3& centre, double size);

// `count` triangles around (addTriangleAround) centres drawn by `centre`, of sizes drawn by
// `size`, each drawn in that order: scenes whose centroids coincide, or lie on a line or a plane,
// where a builder finds no split. Finalized.
Scene makeTrianglesAroundScene(std::string name, size_t count, uint64_t seed,
                               const std::function<DVec3(StressRng&)>& centre,
                               const std::function<double(StressRng&)>& size);

// Builders' edge cases (not closed): n copies of one triangle; n small triangles whose
// centres lie on one line; one huge triangle among n tiny ones.
Scene makeIdenticalTrianglesScene(size_t n);
Scene makeCollinearCentroidsScene(size_t n, uint64_t seed);
Scene makeHugeAmongTinyScene(size_t n, uint64_t seed);

}  // namespace bvhlab
