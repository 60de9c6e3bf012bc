// Every registered accelerator against naive (float) and the double-precision oracle, on closed
// meshes for watertightness (with Embree's bounds), on non-convex polygons and on a few real
// scene files. The generated scenes and ray kinds are the conformance suite's (`bvhlab check`,
// tests/accel/verify/test_conformance.cpp). Parameterised over acceleratorInfos(), so new accelerators
// are picked up as they are registered ("naive" included: it is then checked against the oracle).
//
// Failure policy: for our own accelerators every answer the oracle's judge calls Wrong fails,
// as does any violation of the interface contract (return value vs hit, isOccluded vs
// findNearest, query counts) and any leak through a closed mesh. Embree (without ROBUST it
// is known to leak at edges) is held to bounds instead: its confirmed errors are printed and
// recorded (RecordProperty), and fail only above 1 % of a ray set; on the watertightness
// probes (every ray aimed exactly at an edge or a vertex) see externalVariants() below.
#include "accel/naive/naive_accelerator.h"
#include "accel/registry.h"
#include "accel/verify/comparison.h"
#include "accel/verify/conformance.h"
#include "accel/verify/generated_scenes.h"
#include "accel/verify/ray_generators.h"
#include "accel/verify/verify_keys.h"
#include "accel/verify/watertight_probe.h"
#include "framework/core/timed_build.h"
#include "framework/scene/procedural.h"
#include "framework/scene/scene_loader.h"
#include "tests/support/polygons.h"
#include "tests/support/random_geometry.h"
#include "tests/support/registered_accelerators.h"
#include "tests/support/test_paths.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

namespace bvhlab {
namespace {

using namespace bvhlab::verify;
using namespace bvhlab::test;  // polygons and random geometry

// One scene with its oracle and, per ray kind, the rays and naive's and the oracle's answers:
// computed once, shared by every accelerator's run.
struct SceneCase {
    std::unique_ptr<Scene> scene;
    std::unique_ptr<Oracle> oracle;
    std::map<RayKind, std::vector<Ray>> rays;
    std::map<RayKind, Reference> reference;
};

SceneCase& sceneCase(const std::string& key, const std::function<Scene()>& make, const std::vector<RayKind>& kinds,
                     const std::function<size_t(const Scene&, RayKind)>& count) {
    static std::map<std::string, std::unique_ptr<SceneCase>> cache;
    auto& slot = cache[key];
    if (!slot) {
        slot = std::make_unique<SceneCase>();
        slot->scene = std::make_unique<Scene>(make());
        const Scene& scene = *slot->scene;
        slot->oracle = std::make_unique<Oracle>(scene.primitives());
        NaiveAccelerator naive;
        naive.build(scene.primitives());
        uint32_t seed = 2166136261u;  // FNV-1a of the key: the same rays on every platform
        for (const char ch : key) seed = (seed ^ uint8_t(ch)) * 16777619u;
        for (RayKind kind : kinds) {
            slot->rays[kind] = generateRays(kind, scene.primitives(), scene.bounds, count(scene, kind), ++seed);
            slot->reference[kind] = computeReference(naive, *slot->oracle, slot->rays[kind]);
        }
    }
    return *slot;
}

class AccelCorrectness : public ::testing::TestWithParam<std::string> {
protected:
    std::unique_ptr<Accelerator> make() const { return createAccelerator(GetParam(), Env(verify::verifyKeys())); }
    bool external() const { return isExternal(GetParam()); }

    // Checks one comparison report against the failure policy.
    void check(const std::string& label, const ComparisonReport& r) {
        const std::string key = GetParam() + "." + label;
        if (!external()) {
            EXPECT_EQ(r.failures(), 0u) << GetParam() << " on " << label << ": " << r.summary();
            if (r.naiveOnlyWrong > 0)
                std::printf("[ NOTE     ] %s on %s: naive judged wrong on %zu rays where %s is not\n",
                            GetParam().c_str(), label.c_str(), r.naiveOnlyWrong, GetParam().c_str());
            return;
        }
        RecordProperty(key + ".rays", int(r.rays));
        RecordProperty(key + ".oracle_confirmed_errors", int(r.accelWrong));
        RecordProperty(key + ".contract_violations", int(r.failures() - r.accelWrong));
        if (r.failures() > 0)
            std::printf(
                "[ REPORT   ] %s on %s: %zu oracle-confirmed errors, %zu contract violations in %zu rays\n  %s\n",
                GetParam().c_str(), label.c_str(), r.accelWrong, r.failures() - r.accelWrong, r.rays,
                r.summary().c_str());
        EXPECT_LE(double(r.failures()), kExternalBound * double(r.rays))
            << GetParam() << " on " << label << " exceeds the bound for known deviations: " << r.summary();
    }

    // Builds the accelerator over the case's scene and runs every ray kind.
    void runScene(const std::string& name, const std::function<Scene()>& makeScene,
                  const std::vector<RayKind>& kinds = std::vector<RayKind>(std::begin(kAllRayKinds),
                                                                           std::end(kAllRayKinds)),
                  const std::function<size_t(const Scene&, RayKind)>& count = raysPerKind) {
        SceneCase& c = sceneCase(name, makeScene, kinds, count);
        const auto accel = make();
        const BuildStats stats = timedBuild(*accel, c.scene->primitives());
        EXPECT_EQ(stats.primitives, c.scene->validPrimitives.size()) << name;
        for (RayKind kind : kinds) {
            const std::string label = name + "/" + rayKindName(kind);
            SCOPED_TRACE(label);
            check(label, compareWithReference(*accel, c.reference.at(kind), *c.oracle, c.rays.at(kind)));
        }
    }
};

// --- Watertightness on closed meshes -----------------------------------------------------------

// Closed meshes beside the stress suite's (test_stress.cpp): a small sphere far off the origin,
// and a box whose faces repeat their corners (addBox), probed at edges and vertices.
struct ClosedMesh {
    std::string name;
    Scene scene;
    size_t probes;
};

std::vector<ClosedMesh> closedMeshes() {
    std::vector<ClosedMesh> meshes;
    auto add = [&](std::string name, size_t probes, const std::function<void(Scene&)>& fill) {
        Scene s;
        fill(s);
        s.finalize();
        meshes.push_back({std::move(name), std::move(s), probes});
    };
    add("icosphere3", 10000, [](Scene& s) { addIcosphere(s, Vec3(0.3f, -0.2f, 0.1f), 1.7f, 3, 0); });
    add("icosphere_small", 3000, [](Scene& s) { addIcosphere(s, Vec3(100.0f, 50.0f, -20.0f), 0.01f, 1, 0); });
    add("box", 1000, [](Scene& s) { addBox(s, Vec3(-1.0f, -0.5f, 0.25f), Vec3(2.0f, 1.5f, 0.75f), 0); });
    add("torus", 12000, [](Scene& s) { addTorus(s, Vec3(1.0f, 2.0f, -1.0f), 2.0f, 0.6f, 40, 20, 0); });
    return meshes;
}

// Watertightness bounds for external accelerators, per configuration, as fractions of the
// probes through edges and through vertices. Measured for Embree 3.13 on these probes: default
// (non-robust) test, edges 2.8-7.6 % and vertices 8.7-19.6 % leak; with Embree::robust, edges 0 %
// and vertices 0-0.13 %. The default configuration is held only to gross-breakage bounds; robust
// mode to 1 % at edges.
struct ExternalVariant {
    std::string label;
    std::vector<std::pair<std::string, std::string>> env;
    double edgeBound, vertexBound;
};

std::vector<ExternalVariant> externalVariants(const std::string& name) {
    if (name == "embree")
        return {{"default", {}, 0.20, 0.40}, {"robust", {{"Embree::robust", "true"}}, kExternalBound, 0.15}};
    return {{"default", {}, kExternalBound, kExternalBound}};
}

TEST_P(AccelCorrectness, ClosedMeshesAreWatertight) {
    const std::vector<ExternalVariant> variants =
        external() ? externalVariants(GetParam()) : std::vector<ExternalVariant>{{"default", {}, 0.0, 0.0}};
    for (const ClosedMesh& mesh : closedMeshes()) {
        SCOPED_TRACE(mesh.name);
        const MeshTopology topology = MeshTopology::of(mesh.scene);
        ASSERT_TRUE(topology.closed()) << topology.summary();
        ProbeOptions options;
        options.rays = mesh.probes;
        options.seed = mesh.scene.triangleCount();
        const ProbeSet probes = makeWatertightProbes(topology, options);
        ASSERT_EQ(probes.probes.size(), mesh.probes);
        for (const ExternalVariant& variant : variants) {
            SCOPED_TRACE(variant.label);
            Env env(verifyKeys());
            for (const auto& [key, value] : variant.env) env.set(key, value, "test");
            const auto accel = createAccelerator(GetParam(), env);
            accel->build(mesh.scene.primitives());
            const LeakStats c = countLeaks(*accel, probes.probes);
            ASSERT_GT(c.edgeRays, 0u);
            ASSERT_GT(c.vertexRays, 0u);
            std::string detail;
            for (const std::string& e : c.examples) detail += "\n    " + e;
            if (!external()) {
                EXPECT_EQ(c.leaks, 0u) << GetParam() << " leaks through " << mesh.name << " on " << c.edgeLeaks
                                       << " of " << c.edgeRays << " edge probes and " << c.vertexLeaks << " of "
                                       << c.vertexRays << " vertex probes:" << detail;
                EXPECT_EQ(c.occlusionLeaks, 0u) << GetParam() << ": isOccluded false for a probe into " << mesh.name;
                EXPECT_EQ(c.batchLeaks + c.batchOcclusionLeaks, 0u) << GetParam() << ": the batch calls leak" << detail;
                continue;
            }
            const std::string key = GetParam() + "." + variant.label + ".watertight." + mesh.name;
            RecordProperty(key + ".edge_probes", int(c.edgeRays));
            RecordProperty(key + ".edge_leaks", int(c.edgeLeaks));
            RecordProperty(key + ".vertex_probes", int(c.vertexRays));
            RecordProperty(key + ".vertex_leaks", int(c.vertexLeaks));
            RecordProperty(key + ".not_occluded", int(c.occlusionLeaks));
            if (c.leaks > 0)
                std::printf(
                    "[ REPORT   ] %s (%s) leaks through %s: edges %zu of %zu (%.2f %%, bound %.0f %%), "
                    "vertices %zu of %zu (%.2f %%, bound %.0f %%)%s\n",
                    GetParam().c_str(), variant.label.c_str(), mesh.name.c_str(), c.edgeLeaks, c.edgeRays,
                    100.0 * double(c.edgeLeaks) / double(c.edgeRays), 100.0 * variant.edgeBound, c.vertexLeaks,
                    c.vertexRays, 100.0 * double(c.vertexLeaks) / double(c.vertexRays), 100.0 * variant.vertexBound,
                    detail.c_str());
            EXPECT_LE(double(c.edgeLeaks), variant.edgeBound * double(c.edgeRays)) << variant.label << detail;
            EXPECT_LE(double(c.vertexLeaks), variant.vertexBound * double(c.vertexRays)) << variant.label << detail;
            EXPECT_LE(double(c.occlusionLeaks), std::max(variant.edgeBound, variant.vertexBound) * double(c.rays))
                << variant.label;
        }
    }
}

// NFF faces that are not convex (stars, combs, notched squares, gears of 144 corners) in
// random planes, as the NFF reader triangulates them: ear-clipped triangles with collinear
// corners and slivers among them.
Scene nonConvexPolygonScene() {
    std::mt19937 rng(26);
    const std::vector<Polygon2> shapes = {starPolygon(), combPolygon(), notchedSquare(), gearPolygon()};
    std::string nff;
    for (int i = 0; i < 200; ++i) {
        const DVec3 u = randomUnit(rng), w = randomUnit(rng);
        const DVec3 v = glm::normalize(glm::cross(w, u));
        const double size = 0.3 + 2.0 * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        nff += nffPolygon(shapes[i % shapes.size()], {randomPointWithin(rng, 8.0), size * u, size * v});
    }
    Scene scene = readNff("polygons.nff", nff);
    scene.finalize();
    return scene;
}

TEST_P(AccelCorrectness, NonConvexPolygons) { runScene("nonconvex_polygons", nonConvexPolygonScene); }

// --- Scene files --------------------------------------------------------------------------------

std::filesystem::path sharedScenes() { return std::filesystem::path(test::sourceTree()) / ".." / "shared" / "scenes"; }

const std::vector<RayKind> kFileRayKinds = {RayKind::Outside,     RayKind::Inside,       RayKind::EdgeAimed,
                                            RayKind::VertexAimed, RayKind::AxisParallel, RayKind::Grazing,
                                            RayKind::Interval};

#define FILE_TEST(TestName, relative, raysPerKind)                                              \
    TEST_P(AccelCorrectness, TestName) {                                                        \
        const std::filesystem::path file = sharedScenes() / relative;                           \
        if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " not found";               \
        runScene(                                                                               \
            std::string("file:") + relative, [file] { return loadScene(file); }, kFileRayKinds, \
            [](const Scene&, RayKind) { return size_t(raysPerKind); });                         \
    }

FILE_TEST(SceneFileTeapotNff, "nff/teapot.nff", 1000)
FILE_TEST(SceneFileTetraNff, "nff/tetra.nff", 1000)
FILE_TEST(SceneFileMunichPly, "munich.ply", 250)

INSTANTIATE_TEST_SUITE_P(Registered, AccelCorrectness, ::testing::ValuesIn(test::registeredAccelerators()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace bvhlab
