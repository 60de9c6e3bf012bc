// What the checks of the conformance suite share (conformance.cpp) and the checks themselves,
// one file per family: agreement_checks.cpp, query_checks.cpp, robustness_checks.cpp, cost_check.cpp.
#pragma once

#include "accel/verify/conformance.h"
#include "framework/scene/scene.h"

#include <memory>
#include <string>

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

CheckResult agreement(const Subject& subject, const CheckOptions& options);
CheckResult anyHit(const Subject& subject, const CheckOptions& options);
CheckResult degenerateTriangles(const Subject& subject, const CheckOptions& options);
CheckResult mixedPrimitives(const Subject& subject, const CheckOptions& options);
CheckResult batch(const Subject& subject, const CheckOptions& options);
CheckResult watertight(const Subject& subject, const CheckOptions& options);
CheckResult buildsAtTheEdge(const Subject& subject, const CheckOptions& options);
CheckResult cost(const Subject& subject, const CheckOptions& options);

}  // namespace bvhlab::verify
