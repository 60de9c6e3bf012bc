// Watertightness probes for closed meshes: rays aimed exactly at points on interior edges and at
// vertices, kept only where the answer is unambiguous, and the count of the rays an accelerator
// lets through ("leaks"): the probes of `bvhlab stress`, `bvhlab check` and the tests.
//
// The recipe (docs/accuracy.md, "Robustness"): pick a point p on an interior edge (or a
// vertex), an origin outside along a direction d, and keep the ray only if every triangle
// around p faces it the same way at more than ~6 degrees from grazing. The triangles around p
// then cover a neighbourhood of p as seen along the ray, so p is no silhouette and any
// watertight traversal must report a hit at or before p; t's rounding stays tiny. tmax is
// 1.0001 times the distance to p (unit direction), so a hit must exist in [0, tmax]: a miss is
// a leak.
//
// Rounding is accounted for, not hoped away: the origin is rounded to float first and the
// direction recomputed from it; the angle test is redone on the rounded ray; and p must lie
// farther from every edge bounding the triangles around it (measured across the ray) than a
// generous bound on how far the float ray and the float triangle test can stray from p, so
// that the ray cannot pass through a neighbouring triangle that was not checked.
#pragma once

#include "framework/core/accelerator.h"
#include "framework/scene/scene.h"

#include <span>
#include <string>
#include <vector>

namespace bvhlab::verify {

// The connectivity of a triangle mesh with vertices welded by position (meshes that repeat a
// position per face, like procedural.h's addBox, are handled too). Only valid (non-degenerate)
// primitives take part.
struct MeshTopology {
    struct Face {
        uint32_t v[3];       // welded vertex ids, in the primitive's winding
        uint32_t primitive;  // its primitive index in the scene
        DVec3 normal;        // unit, outward when the mesh's signed volume is positive
    };
    // An edge shared by exactly two faces that traverse it in opposite directions.
    struct Edge {
        uint32_t a, b;
        uint32_t faces[2];
    };

    std::vector<DVec3> vertices;  // welded positions
    std::vector<Face> faces;
    std::vector<Edge> interiorEdges;
    std::vector<uint32_t> starOffsets;  // faces around vertex v: starFaces[starOffsets[v] .. starOffsets[v + 1])
    std::vector<uint32_t> starFaces;
    std::vector<uint8_t> vertexInterior;  // every edge at the vertex is interior
    size_t boundaryEdges = 0;             // used by one face
    size_t nonManifoldEdges = 0;          // used by more than two faces
    size_t inconsistentEdges = 0;         // two faces, same direction (winding flips)
    double signedVolume = 0.0;            // of the faces as wound (before any flip)
    Bounds3 bounds;

    bool closed() const { return boundaryEdges == 0 && nonManifoldEdges == 0 && inconsistentEdges == 0; }
    std::string summary() const;

    static MeshTopology of(const Scene& scene);
};

struct ProbeOptions {
    size_t rays = 1000000;
    uint64_t seed = 1;
    double vertexFraction = 0.3;  // the rest aim at points on interior edges
    double minDegreesFromGrazing = 6.0;
    double tmaxFactor = 1.0001;  // tmax = factor * distance to the aimed-at point
    // Origins lie at distances log-uniform in [minDistance * local edge length, maxDistance * mesh radius].
    double minDistance = 0.25;
    double maxDistance = 4.0;
    int maxAttemptsPerRay = 64;  // candidate points tried before giving up on a ray
};

struct WatertightProbeRay {
    Ray ray;           // unit direction, tmin 0, tmax = tmaxFactor * distance to the point
    DVec3 target;      // the point aimed at
    uint32_t feature;  // welded vertex id, or index into MeshTopology::interiorEdges
    bool atVertex;
};

struct ProbeSet {
    std::vector<WatertightProbeRay> probes;
    size_t candidates = 0;  // points tried
    size_t rejected = 0;    // of them, not unambiguous (silhouette, grazing, too close to an edge)
};

// Deterministic for a given mesh and options (own generator, no std distributions).
ProbeSet makeWatertightProbes(const MeshTopology& mesh, const ProbeOptions& options = {});

struct LeakStats {
    size_t rays = 0, leaks = 0;  // leaks: findNearest found nothing in [0, tmax]
    size_t edgeRays = 0, edgeLeaks = 0, vertexRays = 0, vertexLeaks = 0;
    size_t occlusionLeaks = 0;  // isOccluded answered false
    // The same probes through the batch calls (the wide layouts trace them as packets): a leak
    // there is one of the packet traversal, even where the single-ray calls hold.
    size_t batchLeaks = 0, batchOcclusionLeaks = 0;
    std::vector<std::string> examples;  // the first few leaks, full precision

    double perMillion() const { return rays ? 1e6 * double(leaks) / double(rays) : 0.0; }
    double occlusionPerMillion() const { return rays ? 1e6 * double(occlusionLeaks) / double(rays) : 0.0; }
};

// Traces every probe with findNearest and isOccluded, and again with findNearestBatch and
// isOccludedBatch, under either coherence hint, over each run of consecutive probes (in
// parallel with TBB; counters are not kept). `threads` 0 = all hardware threads.
LeakStats countLeaks(const Accelerator& accel, std::span<const WatertightProbeRay> probes, int threads = 0,
                     size_t maxExamples = 5);

}  // namespace bvhlab::verify
