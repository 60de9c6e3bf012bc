#include "accel/verify/conformance.h"

#include "accel/verify/conformance_checks.h"
#include "framework/core/error.h"
#include "framework/core/timed_build.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace bvhlab::verify {

CheckResult newResult(std::string check, std::string unit) {
    CheckResult result;
    result.check = std::move(check);
    result.unit = std::move(unit);
    return result;
}

size_t scaled(size_t count, const CheckOptions& options) {
    return std::max<size_t>(1, size_t(std::llround(double(count) * options.rayScale)));
}

void reportProgress(const CheckOptions& options, uint64_t done, uint64_t total) {
    if (options.progress) options.progress(done, total);
}

void addExample(CheckResult& result, const CheckOptions& options, const std::string& scene, const std::string& what) {
    if (result.examples.size() < options.maxExamples)
        result.examples.push_back(fmt::format("{} on {}: {}", result.check, scene, what));
}

std::unique_ptr<Accelerator> buildOn(const Subject& subject, const Scene& scene, CheckResult& result,
                                     const CheckOptions& options, BuildStats* stats) {
    auto accel = subject.make();
    const BuildStats s = timedBuild(*accel, scene.primitives());
    if (s.primitives != scene.validPrimitives.size()) {
        ++result.failures;
        addExample(result, options, scene.name,
                   fmt::format("built over {} primitives, the scene has {} valid ones", s.primitives,
                               scene.validPrimitives.size()));
    }
    if (stats) *stats = s;
    return accel;
}

Scene trianglesOf(Scene scene) {
    scene.spheres.clear();
    scene.sphereMaterialIds.clear();
    scene.cones.clear();
    scene.coneMaterialIds.clear();
    scene.finalize();
    return scene;
}

std::vector<NamedSceneFactory> userScenes(const CheckOptions& options) {
    std::vector<NamedSceneFactory> scenes;
    for (const UserScene& user : options.scenes)
        scenes.push_back({user.scene.name, [make = user.scene.make] { return trianglesOf(make()); }});
    return scenes;
}

bool isExternal(std::string_view accelerator) { return accelerator.starts_with("embree"); }

bool batchTracesPackets(std::string_view accelerator) {
    return !isExternal(accelerator) && (accelerator.ends_with('4') || accelerator.ends_with('8'));
}

bool sameCounters(const QueryCounters& a, const QueryCounters& b) {
    return a.queries == b.queries &&
           std::ranges::all_of(kQueryCounters, [&](const QueryCounter& c) { return a.*c.count == b.*c.count; });
}

bool sameQueries(const QueryCounters& a, const QueryCounters& b) {
    return a.queries == b.queries && a.sphereTests == b.sphereTests && a.coneTests == b.coneTests;
}

const std::vector<CheckInfo>& conformanceChecks() {
    static const std::vector<CheckInfo> checks = {
        {"agreement", "closest hit against the double-precision reference on every generated scene and ray kind",
         agreement, true},
        {"any-hit", "isOccluded answers as the closest hit does, and nothing blocks a ray before it", anyHit, true},
        {"batch", "findNearestBatch/isOccludedBatch answer and count as the single-ray calls", batch, true},
        {"mixed-primitives", "triangles, spheres and cones against a double brute force (if supported)",
         mixedPrimitives},
        {"degenerate-triangles", "degenerate triangles mixed in are never hit; rays aimed at them",
         degenerateTriangles},
        {"watertight", "probes at the edges and vertices of closed meshes do not leak (if promised)", watertight},
        {"builds-at-the-edge", "bounded time, memory and depth on degenerate inputs, answers as naive's",
         buildsAtTheEdge},
        {"update",
         "after the primitives moved, the updated structure answers as the reference and a fresh build do, without "
         "leaks (if it has an update)",
         update, true},
        {"cost",
         fmt::format("N_IT + N_TR per ray against sahbvh's on a mid-size scene: a warning past {:g}x", kCostFactor),
         cost},
    };
    return checks;
}

std::vector<std::string> checkNames() {
    std::vector<std::string> names;
    for (const CheckInfo& c : conformanceChecks()) names.push_back(c.name);
    return names;
}

const CheckInfo& findCheck(const std::string& name) {
    for (const CheckInfo& c : conformanceChecks())
        if (c.name == name) return c;
    throw InputError(fmt::format("unknown check '{}' (known: {})", name, fmt::join(checkNames(), ", ")));
}

CheckResult runCheck(const std::string& name, const Subject& subject, const CheckOptions& options) {
    const CheckInfo& info = findCheck(name);
    const auto start = std::chrono::steady_clock::now();
    CheckResult result = info.run(subject, options);
    result.check = info.name;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace bvhlab::verify
