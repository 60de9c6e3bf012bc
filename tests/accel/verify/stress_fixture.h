// The accelerators the stress tests run over (every registered one, and Embree with
// RTC_SCENE_FLAG_ROBUST), the fixture that builds them and holds ours to zero, and the probed
// closed meshes: shared by test_stress.cpp, test_stress_rays.cpp and test_watertight_probes.cpp.
#pragma once

#include "accel/registry.h"
#include "accel/verify/closed_meshes.h"
#include "accel/verify/verify_keys.h"
#include "accel/verify/watertight_probe.h"
#include "framework/core/timed_build.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace bvhlab::verify {

struct Variant {
    std::string label;  // gtest-safe
    std::string name;   // in the registry
    std::vector<std::pair<std::string, std::string>> env;
    bool external;  // reported, not failed (Embree)
};

inline std::vector<Variant> variants() {
    std::vector<Variant> list;
    for (const AcceleratorInfo& info : acceleratorInfos()) {
        const bool external = info.name == "embree";
        list.push_back({info.name, info.name, {}, external});
        if (info.name == "embree") list.push_back({"embree_robust", "embree", {{"Embree::robust", "true"}}, true});
    }
    return list;
}

// Naive tests every triangle: it runs only on meshes up to this size.
constexpr size_t kNaiveMaxTriangles = 5000;

inline void PrintTo(const Variant& v, std::ostream* out) { *out << v.label; }

class Stress : public ::testing::TestWithParam<Variant> {
protected:
    const Variant& variant() const { return GetParam(); }
    bool external() const { return variant().external; }
    bool isNaive() const { return variant().name == "naive"; }

    std::unique_ptr<Accelerator> build(const Scene& scene, BuildStats* stats = nullptr) const {
        Env env(verifyKeys());
        for (const auto& [key, value] : variant().env) env.set(key, value, "test");
        auto accel = createAccelerator(variant().name, env);
        const BuildStats s = timedBuild(*accel, scene.primitives());
        if (stats) *stats = s;
        return accel;
    }

    // Ours: must be 0. External: recorded and printed.
    void expectZero(const std::string& what, size_t count, size_t of, const std::vector<std::string>& examples = {}) {
        std::string detail;
        for (const std::string& e : examples) detail += "\n    " + e;
        if (!external()) {
            EXPECT_EQ(count, 0u) << variant().label << ": " << what << " (" << count << " of " << of << ")" << detail;
            return;
        }
        std::string key = variant().label + "." + what;
        std::replace(key.begin(), key.end(), ' ', '_');
        RecordProperty(key, int(count));
        if (count)
            std::printf("[ REPORT   ] %s: %s: %zu of %zu (%.0f per million)\n", variant().label.c_str(), what.c_str(),
                        count, of, 1e6 * double(count) / double(std::max<size_t>(of, 1)));
    }
};

struct ProbedMesh {
    Scene scene;
    MeshTopology topology;
    ProbeSet probes;
};

// The closed meshes of the stress tests, each with 20,000 probes.
inline const std::vector<ProbedMesh>& probedMeshes() {
    static const std::vector<ProbedMesh> meshes = [] {
        std::vector<ProbedMesh> list;
        for (Scene scene : {makeIcosphereMesh(3), makeIcosphereMesh(5), makeSubdividedCubeMesh(8),
                            makeSubdividedCubeMesh(32), makeTorusMesh(48, 24), makeTorusMesh(128, 64)}) {
            MeshTopology topology = MeshTopology::of(scene);
            ProbeOptions options;
            options.rays = 20000;
            options.seed = scene.triangleCount();
            ProbeSet probes = makeWatertightProbes(topology, options);
            list.push_back({std::move(scene), std::move(topology), std::move(probes)});
        }
        return list;
    }();
    return meshes;
}

}  // namespace bvhlab::verify
