// The checks of the robustness stress suite that `bvhlab stress`, the conformance suite and
// tests/accel/verify/test_stress.cpp share: one scale/translation case, one shadow-acne render,
// one build at the edge. The accelerator under check is made by the caller.
#pragma once

#include "accel/verify/watertight_probe.h"
#include "framework/core/accelerator.h"
#include "framework/scene/scene.h"

#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace bvhlab::verify {

// One case of the scale/translation sweep: `accel` is built over
// transformedScene(base, scale, offset) = `scene`; `baseRays` and `baseHits` are rays in the
// base scene and the base answers of the same kind of accelerator; `probes` are watertightness
// probes of the transformed scene.
struct TransformCheck {
    LeakStats leaks;            // of the watertightness probes
    size_t compared = 0;        // base rays whose answer is unambiguous (hit far from every edge)
    size_t otherPrimitive = 0;  // of them, the moved ray hit another primitive (or nothing)
    size_t tNotScaling = 0;     // the same primitive, but t / scale differs by more than 1e-4 relative
    std::vector<std::string> examples;

    bool passed() const {
        return leaks.leaks == 0 && leaks.occlusionLeaks == 0 && otherPrimitive == 0 && tNotScaling == 0;
    }
};
TransformCheck checkTransformed(const Accelerator& accel, double scale, const DVec3& offset,
                                std::span<const Ray> baseRays, std::span<const Hit> baseHits,
                                std::span<const WatertightProbeRay> probes, int threads = 0);

// How far a tree's normalised SAH cost may move when the scene is scaled. By a power of two the
// coordinates scale exactly: the same tree, the same cost (to rounding of the cost itself). By a
// decimal scale they round, which flips a builder's choice wherever candidates tie (the stress
// scenes' grids are full of exact ties): the tree changes a little. Measured on those scenes, up
// to 0.2 % for a binary binned SAH, 1.2 % for the wide layouts (a flipped tie moves a triangle
// across a block of eight, which changes a leaf's charge by a whole block), 2.3 % for PLOC (its
// Morton order moves centres on cell boundaries to the next cell); a wrong tree is far beyond.
inline double sahScaleTolerance(double scale) {
    const bool exact = std::exp2(std::round(std::log2(scale))) == scale;
    return exact ? 1e-9 : 3e-2;
}

// Renders `planeScene` (makeDistantPlaneScene: its camera sees only the plane, lit) with and
// without shadows; a pixel is self-shadowed when the shadow ray took its light away.
struct AcneCheck {
    size_t pixels = 0;
    size_t onPlane = 0;       // pixels whose camera ray hit the plane
    size_t selfShadowed = 0;  // darker with shadows than without
    size_t dark = 0;          // not above the ambient term

    // `darkIsFault` false: a plane lit from low may be dim, never self-shadowed.
    bool passed(bool darkIsFault = true) const {
        return onPlane == pixels && selfShadowed == 0 && (!darkIsFault || dark == 0);
    }
};
AcneCheck checkShadowAcne(const Scene& planeScene, const Accelerator& accel, int pixels, int threads = 0);

// Builders at the edge (coincident triangles, centres on one line, a huge triangle among tiny
// ones: edgeBuildScenes, generated_scenes.h): `accel`, not yet built, is built over `scene` and held to bounded
// time (maxSeconds, a bound against a build that hangs or goes quadratic, not a timing) and
// memory (kMaxBytesPerPrimitive), to what it promises (BuildStats::depthBound and leafBound), to
// build over every valid primitive, and to answer `rays` as `reference` does (hitsAgree; naive's
// answers). Shared by `bvhlab stress`, `bvhlab check` and the tests.
inline constexpr size_t kMaxBytesPerPrimitive = 4096;  // ours take under 200
struct EdgeBuildCheck {
    BuildStats stats;
    double seconds = 0.0;               // the build (timedBuild): the lesser of wall and CPU time
    size_t rays = 0, differ = 0;        // answers unlike the reference's
    std::vector<std::string> problems;  // every bound broken, e.g. "depth 70 >= 64"
    std::vector<std::string> examples;  // the first few differing answers, full precision

    bool passed() const { return problems.empty() && differ == 0; }
};
// naive's closest hits for `rays` over `scene`: the reference of the builds at the edge.
std::vector<Hit> naiveAnswers(const Scene& scene, std::span<const Ray> rays, int threads = 0);
EdgeBuildCheck checkEdgeBuild(Accelerator& accel, const Scene& scene, std::span<const Ray> rays,
                              std::span<const Hit> reference, double maxSeconds, int threads = 0,
                              size_t maxExamples = 3);

}  // namespace bvhlab::verify
