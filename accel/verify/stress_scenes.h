// Scenes of the robustness stress suite (`bvhlab stress`, tests/accel/verify/test_stress.cpp)
// besides the closed meshes (closed_meshes.h): a scene scaled and moved, and lit planes far from
// the origin for shadow acne. All deterministic.
#pragma once

#include "framework/scene/scene.h"

#include <vector>

namespace bvhlab::verify {

// The scene with every position mapped to float(scale * p + offset) (computed in double),
// lights and camera likewise; normals and topology unchanged. Finalized.
Scene transformedScene(const Scene& scene, double scale, const DVec3& offset);

// The scale/translation sweep of `bvhlab stress`: scales from 1e-3 to 1e4, decimal ones (which
// round every coordinate) and powers of two (2^-10, 2^13, which scale them exactly); offsets in
// units of the scaled scene's size.
std::vector<double> sweepScales();
std::vector<DVec3> sweepOffsets();

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

// The shadow-acne cases of `bvhlab stress`: planes at 1e4 from the origin must pass; at 1e6
// they are reported (float spacing there is 0.06). The grounds, lit from 5 degrees, must show
// no self-shadowing; their dimness is no fault.
struct AcneCase {
    Scene scene;
    double distance;
    bool mustPass, darkIsFault;
};
std::vector<AcneCase> acneCases();

}  // namespace bvhlab::verify
