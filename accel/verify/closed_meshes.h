// Generated closed meshes, outward-wound, for the watertightness probes (watertight_probe.h) and
// the scale/translation sweep. All deterministic.
#pragma once

#include "framework/scene/scene.h"

#include <functional>
#include <string>
#include <vector>

namespace bvhlab::verify {

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

// `bvhlab stress`'s meshes of a family ("icosphere", "cube" or "torus"): a small and a large one
// (icosphere2 and icosphere6, cube4 and cube64, torus24x12 and torus384x96); none for another name.
std::vector<std::function<Scene()>> closedMeshFamily(const std::string& family);

}  // namespace bvhlab::verify
