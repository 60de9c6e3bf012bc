// The conformance suite of an accelerator (`bvhlab check`, docs/accuracy.md): named checks, each
// over a structure built afresh on generated scenes (and some on the user's, `--scene`), each held
// to what the structure promises.
// The gtest suite (tests/accel/verify/test_conformance.cpp) runs the same checks for every registered
// accelerator; the reference is the double-precision oracle (accel/verify/oracle.h).
#pragma once

#include "accel/verify/generated_scenes.h"
#include "framework/core/accelerator.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace bvhlab::verify {

// The structure under check: its registry name (which decides what it promises) and a way to
// create it unbuilt, configured.
struct Subject {
    std::string name;
    std::function<std::unique_ptr<Accelerator>()> make;
};

// A scene of the user's (`bvhlab check --scene`), which the checks that take scenes run beside
// their generated ones, on its triangles (the reference's: its spheres and cones are left out).
// Its names differ from the generated scenes' (the checks keep a scene's rays by its name).
struct UserScene {
    NamedSceneFactory scene;
    // The same scene after its own motion, for the update check: an animated scene at another
    // frame. Empty for a still scene, which the check moves as its generated ones (movedScene).
    NamedSceneFactory moved;
};

struct CheckOptions {
    double rayScale = 1.0;           // multiplies every ray and probe count
    size_t edgePrimitives = 100000;  // of each builders' edge case
    double edgeMaxSeconds = 0.0;     // a slower edge build fails; 0: the default bound
    size_t maxExamples = 3;          // failures shown per check
    int threads = 0;                 // builds and probes; 0 = all hardware threads
    std::vector<UserScene> scenes;   // checked beside the generated scenes (CheckInfo::takesScenes)
    // Called as the check goes, with units done (scenes, ray sets) of `total`.
    std::function<void(uint64_t done, uint64_t total)> progress;
};

struct CheckResult {
    std::string check;
    std::string unit = "rays";  // what `cases` counts
    size_t scenes = 0;
    size_t cases = 0;     // rays, probes or builds checked
    size_t failures = 0;  // of them, answers (or builds) that break what the structure promises
    bool skipped = false;
    bool warning = false;  // passed, but worth a look (the cost check past its bound)
    std::string note;      // why skipped, or what was reported and not failed
    // The first few failures, each naming the check, the scene, the ray (org, dir, tmin, tmax,
    // "%.9g") and the structure's and the reference's answers.
    std::vector<std::string> examples;
    double seconds = 0.0;

    bool passed() const { return failures == 0; }
};

struct CheckInfo {
    std::string name;
    std::string description;
    CheckResult (*run)(const Subject&, const CheckOptions&);
    bool takesScenes = false;  // runs CheckOptions::scenes too
};

// Every check, in the order `bvhlab check` runs them.
const std::vector<CheckInfo>& conformanceChecks();
std::vector<std::string> checkNames();
// Throws InputError for a name that is no check, listing the known ones.
const CheckInfo& findCheck(const std::string& name);
CheckResult runCheck(const std::string& name, const Subject& subject, const CheckOptions& options = {});

// What a structure promises, by its name: ours are watertight and answer batches bit for bit as
// single rays; Embree (names starting with "embree") is held to bounds instead (docs/accuracy.md).
bool isExternal(std::string_view accelerator);
// Known deviations of an external structure (Embree without ROBUST leaks at edges) are reported,
// and fail only above this fraction of a ray set.
inline constexpr double kExternalBound = 0.01;
inline bool batchIsBitExact(std::string_view accelerator) { return !isExternal(accelerator); }
// Ours of the wide layouts (builder_table.h names them NAME4, NAME8) trace batches as packets:
// the same answers, but a ray's N_IT and N_TR follow the packet's visit order
// (docs/architecture.md), so the batch calls' work differs from the single-ray calls'; their
// queries and quadric tests do not.
bool batchTracesPackets(std::string_view accelerator);

// Every count of a and b is the same.
bool sameCounters(const QueryCounters& a, const QueryCounters& b);
// The counts a batch traced as packets keeps from the single-ray calls: queries, sphere and cone tests.
bool sameQueries(const QueryCounters& a, const QueryCounters& b);

}  // namespace bvhlab::verify
