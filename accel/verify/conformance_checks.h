// What the checks of the conformance suite share (conformance.cpp) and the checks themselves,
// one file per family: agreement_checks.cpp, query_checks.cpp, robustness_checks.cpp, cost_check.cpp,
// update_check.cpp.
#pragma once

#include "accel/verify/comparison.h"
#include "accel/verify/conformance.h"
#include "accel/verify/generated_scenes.h"
#include "accel/verify/ray_generators.h"
#include "accel/verify/watertight_probe.h"
#include "framework/scene/scene.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace bvhlab::verify {

// A structure that answers right but works this many times harder per ray than sahbvh is
// warned about, not failed (docs/accuracy.md: how far our own structures are from it).
inline constexpr double kCostFactor = 10.0;

CheckResult newResult(std::string check, std::string unit = "rays");
// `count` times CheckOptions::rayScale, at least 1.
size_t scaled(size_t count, const CheckOptions& options);
void reportProgress(const CheckOptions& options, uint64_t done, uint64_t total);
// Adds a failure's text (naming the check and the scene) while there is room.
void addExample(CheckResult& result, const CheckOptions& options, const std::string& scene, const std::string& what);
// The subject built over `scene`; a build over fewer primitives than the scene's valid ones fails.
std::unique_ptr<Accelerator> buildOn(const Subject& subject, const Scene& scene, CheckResult& result,
                                     const CheckOptions& options, BuildStats* stats = nullptr);

// The scene without its spheres and cones (the oracle's are triangles only); the triangles keep
// their indices.
Scene trianglesOf(Scene scene);
// The user's scenes (CheckOptions::scenes) as the checks take them: their triangles.
std::vector<NamedSceneFactory> userScenes(const CheckOptions& options);

// One scene with its oracle and, per ray kind, the rays and (when a check judges answers) the
// oracle's answers: computed once per process (by the factory's name and the ray scale), shared
// by every structure and check. `extraRays` join as a last set ("aimed").
struct SceneCase {
    Scene scene;
    std::unique_ptr<Oracle> oracle;
    std::vector<std::pair<RayKind, std::vector<Ray>>> rays;
    std::vector<Reference> reference;
};
const SceneCase& sceneCase(const NamedSceneFactory& factory, const std::vector<Ray>& extraRays, double rayScale,
                           bool judged);
// The generated scenes of the agreement and any-hit checks.
std::vector<NamedSceneFactory> agreementScenes();

// The closed meshes of the watertight check, each with its probes (CheckOptions::rayScale
// times `rays`), computed once per process; `moved`: the meshes after movedScene.
using ProbedMeshes = std::vector<std::pair<Scene, ProbeSet>>;
const ProbedMeshes& probedMeshes(const CheckOptions& options, size_t rays, bool moved);
// Adds the leaks of `stats` on `scene` to `result`: failures where the subject promises
// watertightness, else counted in `reported`.
void tallyLeaks(const Subject& subject, const CheckOptions& options, const Scene& scene, const LeakStats& stats,
                CheckResult& result, size_t& reported);

CheckResult agreement(const Subject& subject, const CheckOptions& options);
CheckResult anyHit(const Subject& subject, const CheckOptions& options);
CheckResult degenerateTriangles(const Subject& subject, const CheckOptions& options);
CheckResult mixedPrimitives(const Subject& subject, const CheckOptions& options);
CheckResult batch(const Subject& subject, const CheckOptions& options);
CheckResult watertight(const Subject& subject, const CheckOptions& options);
CheckResult buildsAtTheEdge(const Subject& subject, const CheckOptions& options);
CheckResult cost(const Subject& subject, const CheckOptions& options);
CheckResult update(const Subject& subject, const CheckOptions& options);

}  // namespace bvhlab::verify
