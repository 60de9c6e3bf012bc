// The generated scenes of verification: random soups, terrain, coincident and degenerate
// triangles, centroids that coincide or lie on a line or a plane (where a builder finds no
// split), the builders' edge cases, and the scenes with spheres and cones. Each returns a
// finalized scene, the same for a given seed on every platform (VerifyRng, verify_rng.h).
#pragma once

#include "accel/verify/verify_rng.h"
#include "framework/scene/scene.h"

#include <functional>
#include <string>
#include <vector>

namespace bvhlab::verify {

// `count` triangles of log-uniform sizes in [minSize, maxSize], around uniform points of a cube
// `extent` across, centred on the origin.
Scene makeSoupScene(size_t count, uint32_t seed, float minSize = 1e-6f, float maxSize = 1e3f, float extent = 100.0f);
Scene makeTerrainScene(int cells, uint32_t seed);  // cells x cells height field, 2 triangles per cell
// The cost check's scene, about 32,000 triangles of sizes and densities as different as a
// rendered scene's: a large floor, boxes, a finely tessellated sphere and torus, small
// triangles scattered in the air.
Scene makeCostScene();
// `groups` random triangles, each `copies` times over in turns: as it is, again, with its winding
// reversed, with its vertices rotated; and, if `slid`, once more slid within its plane to overlap
// the others.
Scene makeCoincidentScene(size_t groups, size_t copies, bool slid, uint64_t seed);
// A soup with degenerate triangles (points, exact segments, repeated vertices, NaN and infinite
// vertices) mixed in at random places.
Scene makeDegenerateMixScene(size_t count, uint32_t seed);
// One huge triangle among n tiny ones.
Scene makeHugeAmongTinyScene(size_t n, uint64_t seed);

// A random triangle around `centre`: vertices centre + a, centre + b and centre - a - b for
// random a, b of length `size`, so that its centroid is `centre` (exactly in double; the float
// centroid is within rounding of it).
void addTriangleAround(Scene& scene, VerifyRng& rng, const DVec3& centre, double size);

// `count` triangles around (addTriangleAround) centres drawn by `centre`, of sizes drawn by
// `size`, each drawn in that order. Finalized.
Scene makeTrianglesAroundScene(std::string name, size_t count, uint64_t seed,
                               const std::function<DVec3(VerifyRng&)>& centre,
                               const std::function<double(VerifyRng&)>& size);
// Centroids on one line, in a plane, at one point.
Scene makeCollinearCentroidsScene(size_t count, uint64_t seed);
Scene makeCentroidsOnPlaneScene(size_t count, uint32_t seed);
Scene makeCentroidsAtPointScene(size_t count, uint32_t seed);

// A scene built from explicit triangles (three positions each), finalized.
Scene sceneFromTriangles(const std::vector<Triangle>& triangles, const std::string& name);

struct NamedSceneFactory {
    std::string name;
    std::function<Scene()> make;
};
// Every generated scene the correctness suite runs, each at most ~10k triangles.
const std::vector<NamedSceneFactory>& generatedScenes();
// The builders' edge cases, n triangles each: coincident ones, centres on one line, one huge
// triangle among tiny ones (`bvhlab stress`'s builders and the builds-at-the-edge check).
std::vector<NamedSceneFactory> edgeBuildScenes(size_t n, uint64_t seed);

// The scenes of the mixed-primitives and batch checks, also used by the tests: triangles,
// spheres (some negative radius) and cones with one degenerate of each kind; closed meshes, a
// floor, spheres and cones; and random, axis-parallel, behind-the-origin, empty and NaN rays.
Scene makeMixedScene(uint32_t seed);
Scene makeBatchScene();
std::vector<Ray> makeBatchRays();

}  // namespace bvhlab::verify
