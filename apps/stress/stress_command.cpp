// `bvhlab stress`: the robustness stress suite at full size (docs/accuracy.md, "Robustness").
//  - watertight: >= 1e6 rays per closed mesh aimed exactly at interior edges and vertices
//    (accel/verify/watertight_probe.h), through the single-ray and the batch calls (packets,
//    for the wide layouts); leaks per million for every accelerator, naive only on
//    small meshes; the generated meshes plus the closed scans igea.ply and a10.obj.
//  - sweep: one scene scaled by 1e-3 ... 1e4 and moved by up to 10x its size along the axes:
//    no leaks, the same primitives hit, t scaling with the scene, the SAH cost unchanged.
//  - acne: a lit plane 1e4 from the origin, rendered with and without shadows: no pixel may
//    lose its light to its own surface.
//  - builders: 1e6 coincident triangles, 1e6 centres on one line, one huge triangle among 1e6
//    tiny ones: build time, depth, and answers against naive.
// Tables on stdout, JSON in --out, progress on stderr. Exit code 1 when one of our
// accelerators (not Embree, which is reported only) fails a check.
#include "accel/registry.h"
#include "accel/verify/closed_meshes.h"
#include "accel/verify/conformance.h"
#include "accel/verify/generated_scenes.h"
#include "accel/verify/ray_generators.h"
#include "accel/verify/stress_checks.h"
#include "accel/verify/stress_scenes.h"
#include "accel/verify/watertight_probe.h"
#include "apps/cli/command_line.h"
#include "apps/cli/commands.h"
#include "apps/runtime/accel_config.h"
#include "apps/runtime/app_keys.h"
#include "apps/runtime/comma_list.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/program_keys.h"
#include "apps/runtime/run_record.h"
#include "apps/runtime/scene_list.h"
#include "apps/runtime/scene_loading.h"
#include "framework/config/common_keys.h"
#include "framework/core/error.h"
#include "framework/core/timed_build.h"
#include "framework/render/camera.h"
#include "framework/render/renderer.h"
#include "framework/report/provenance.h"
#include "framework/scene/scene_loader.h"

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

namespace bvhlab {
namespace {

using namespace verify;

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

struct StressOptions {
    EnvOptions env;
    size_t rays = 1000000;
    // naive (judged by the oracle), every structure of ours, and Embree (reported, not failed).
    std::string accels = fmt::format("naive,{},embree,embree:Embree::robust=true", ourAccelerators());
    std::vector<std::string> scenes = {"icosphere", "cube", "torus", "igea.ply", "a10.obj"};
    std::string parts = "watertight,sweep,acne,builders";
    size_t sweepRays = 100000;
    size_t builderPrims = 1000000;
    size_t naiveMaxTriangles = 5000;
    double builderMaxSeconds = 120.0;
    int acnePixels = 256;
    int threads = 0;
    uint64_t seed = 1;
    std::string out = "out/stress.json";
};

class StressRun {
public:
    StressRun(const StressOptions& options, std::vector<AccelConfig> configs, const Env& env)
        : options_(options), env_(env), configs_(std::move(configs)) {
        checkAccelConfigs(configs_, env_);
        for (const AccelConfig& c : configs_) createAccelerator(c.name, configured(c));  // before any work
        results_ = {{"provenance", provenanceJson()},
                    {"options",
                     {{"rays", options.rays},
                      {"accels", options.accels},
                      {"scenes", options.scenes},
                      {"sweep_rays", options.sweepRays},
                      {"builder_prims", options.builderPrims},
                      {"naive_max_triangles", options.naiveMaxTriangles},
                      {"seed", options.seed},
                      {"threads", options.threads}}},
                    {"failures", nlohmann::json::array()}};
    }

    void run() {
        const std::vector<std::string> parts = splitCommaList(options_.parts);
        auto wanted = [&](const char* part) { return std::find(parts.begin(), parts.end(), part) != parts.end(); };
        for (const std::string& p : parts)
            if (p != "watertight" && p != "sweep" && p != "acne" && p != "builders")
                throw InputError(fmt::format("--parts: unknown part '{}' (known: watertight, sweep, acne, builders)", p));
        if (wanted("watertight")) watertight();
        if (wanted("sweep")) sweep();
        if (wanted("acne")) acne();
        if (wanted("builders")) builders();
    }

    const nlohmann::json& results() const { return results_; }
    bool failed() const { return !results_["failures"].empty(); }

private:
    Env configured(const AccelConfig& config) const {
        Env env = env_;
        env.set(keys::SetRayTracing::threads, std::to_string(options_.threads), "bvhlab stress --threads");
        return accelConfigEnv(config, env);
    }

    std::unique_ptr<Accelerator> build(const AccelConfig& config, const Scene& scene, BuildStats& stats) const {
        auto accel = createAccelerator(config.name, configured(config));
        tbb::task_arena arena(options_.threads > 0 ? options_.threads : tbb::task_arena::automatic);
        arena.execute([&] { stats = timedBuild(*accel, scene.primitives()); });
        return accel;
    }

    void fail(const AccelConfig& config, const std::string& what) {
        const std::string message = fmt::format("{}: {}", config.label, what);
        if (isExternal(config.name)) {
            fmt::print(stderr, "  (reported, not failed: {})\n", message);
            return;
        }
        fmt::print(stderr, "  FAIL {}\n", message);
        results_["failures"].push_back(message);
    }

    // --- watertightness ---------------------------------------------------------------------

    // The meshes --scenes names: generated families (small and large variants), or files.
    std::vector<std::function<std::optional<Scene>()>> meshes() const {
        std::vector<std::function<std::optional<Scene>()>> list;
        for (const std::string& argument : options_.scenes)
            for (const std::string& name : splitCommaList(argument)) {
                const std::vector<std::function<Scene()>> family = closedMeshFamily(name);
                for (const auto& make : family) list.push_back([make]() -> std::optional<Scene> { return make(); });
                if (!family.empty()) continue;
                // What the other commands' --scenes take; one that is not there is skipped, said why.
                std::vector<std::filesystem::path> files;
                try {
                    for (const SceneArgument& scene : expandSceneList({name}, options_.env))
                        files.push_back(sceneFileOf(scene.load(options_.env)));
                } catch (const InputError& missing) {
                    list.push_back([why = std::string(missing.what())]() -> std::optional<Scene> {
                        fmt::print(stderr, "skipping: {}\n", why);
                        return std::nullopt;
                    });
                    continue;
                }
                for (const std::filesystem::path& file : files)
                    list.push_back([file]() -> std::optional<Scene> { return loadScene(file); });
            }
        return list;
    }

    void watertight() {
        fmt::print(stderr, "== watertightness: {} rays per mesh at interior edges and vertices\n", options_.rays);
        nlohmann::json rows = nlohmann::json::array();
        std::string table = fmt::format("{:<16} {:>8} {:<14} {:>9} {:>7} {:>11} {:>9} {:>11} {:>7} {:>9}\n", "mesh", "tris",
                                        "accel", "rays", "leaks", "per million", "any-hit", "per million", "batch",
                                        "batch any");
        for (const auto& make : meshes()) {
            const auto start = Clock::now();
            const std::optional<Scene> scene = make();
            if (!scene) {
                results_["skipped"].push_back("watertight: a scene file was not found");
                continue;
            }
            const MeshTopology topology = MeshTopology::of(*scene);
            ProbeOptions probeOptions;
            probeOptions.rays = options_.rays;
            probeOptions.seed = options_.seed;
            const ProbeSet probes = makeWatertightProbes(topology, probeOptions);
            fmt::print(stderr, "{}: {}; {} probes ({} of {} candidate points rejected) in {:.1f} s\n", scene->name,
                       topology.summary(), probes.probes.size(), probes.rejected, probes.candidates, secondsSince(start));
            for (const AccelConfig& config : configs_) {
                if (config.name == "naive" && scene->triangleCount() > options_.naiveMaxTriangles) continue;
                BuildStats stats;
                const auto accel = build(config, *scene, stats);
                const auto traced = Clock::now();
                const LeakStats leaks = countLeaks(*accel, probes.probes, options_.threads);
                fmt::print(stderr, "  {}: built in {:.0f} ms, {} leaks, {} any-hit leaks (batch: {}, {}) of {} rays in {:.1f} s\n",
                           config.label, stats.buildMs, leaks.leaks, leaks.occlusionLeaks, leaks.batchLeaks,
                           leaks.batchOcclusionLeaks, leaks.rays, secondsSince(traced));
                for (const std::string& e : leaks.examples) fmt::print(stderr, "    {}\n", e);
                if (leaks.leaks || leaks.occlusionLeaks || leaks.batchLeaks || leaks.batchOcclusionLeaks)
                    fail(config, fmt::format("{} leaks and {} any-hit leaks (batch queries: {} and {}) in {} rays through {}",
                                             leaks.leaks, leaks.occlusionLeaks, leaks.batchLeaks, leaks.batchOcclusionLeaks,
                                             leaks.rays, scene->name));
                table += fmt::format("{:<16} {:>8} {:<14} {:>9} {:>7} {:>11.1f} {:>9} {:>11.1f} {:>7} {:>9}\n", scene->name,
                                     scene->triangleCount(), config.label, leaks.rays, leaks.leaks, leaks.perMillion(),
                                     leaks.occlusionLeaks, leaks.occlusionPerMillion(), leaks.batchLeaks,
                                     leaks.batchOcclusionLeaks);
                rows.push_back({{"mesh", scene->name},
                                {"triangles", scene->triangleCount()},
                                {"closed", topology.closed()},
                                {"topology", topology.summary()},
                                {"accel", config.label},
                                {"rays", leaks.rays},
                                {"edge_rays", leaks.edgeRays},
                                {"vertex_rays", leaks.vertexRays},
                                {"leaks", leaks.leaks},
                                {"edge_leaks", leaks.edgeLeaks},
                                {"vertex_leaks", leaks.vertexLeaks},
                                {"leaks_per_million", leaks.perMillion()},
                                {"any_hit_leaks", leaks.occlusionLeaks},
                                {"any_hit_leaks_per_million", leaks.occlusionPerMillion()},
                                {"batch_leaks", leaks.batchLeaks},
                                {"batch_any_hit_leaks", leaks.batchOcclusionLeaks},
                                {"build_ms", stats.buildMs},
                                {"examples", leaks.examples}});
            }
        }
        results_["watertight"] = rows;
        const std::string section =
            "watertightness: rays aimed exactly at interior edges and vertices of closed meshes, tmax = 1.0001 x "
            "distance; a leak is a miss (closest hit), any-hit = isOccluded false; batch, batch any = the same through "
            "findNearestBatch and isOccludedBatch\n";
        fmt::print("{}{}\n", section, table);
    }

    // --- scale and translation --------------------------------------------------------------

    void sweep() {
        const Scene base = makeClosedTrioScene(4, 16, 64, 32);
        const double size = glm::length(DVec3(base.bounds.diagonal()));
        const std::vector<double> scales = sweepScales();
        const std::vector<DVec3> offsets = sweepOffsets();
        const std::vector<Ray> baseRays = raysTowardTriangles(base, std::max<size_t>(options_.sweepRays / 5, 1000), options_.seed);
        fmt::print(stderr, "== scale/translation sweep on {} ({} triangles, size {:.3g}): {} scales x {} offsets, {} probes "
                           "and {} rays toward triangles each\n",
                   base.name, base.triangleCount(), size, scales.size(), offsets.size(), options_.sweepRays, baseRays.size());
        nlohmann::json rows = nlohmann::json::array();
        std::string table = fmt::format("{:<14} {:>7} {:<16} {:>8} {:>6} {:>9} {:>8} {:>10} {:>10}\n", "accel", "scale",
                                        "offset/size", "rays", "leaks", "prim diff", "t diff", "SAH", "SAH rel");
        // The base answers of every accelerator, then each scale and offset with its own probes.
        struct Baseline {
            const AccelConfig* config;
            BuildStats stats;
            std::vector<Hit> hits;
            size_t leaks = 0, mismatches = 0;
        };
        std::vector<Baseline> baselines;
        for (const AccelConfig& config : configs_) {
            if (config.name == "naive" && base.triangleCount() > options_.naiveMaxTriangles) continue;
            Baseline b{&config, {}, std::vector<Hit>(baseRays.size())};
            const auto accel = build(config, base, b.stats);
            QueryCounters counters;
            accel->findNearestBatch(baseRays, b.hits, counters, {});
            baselines.push_back(std::move(b));
        }
        for (double scale : scales)
            for (const DVec3& offsetUnits : offsets) {
                const DVec3 offset = offsetUnits * size * scale;
                const Scene scene = transformedScene(base, scale, offset);
                ProbeOptions probeOptions;
                probeOptions.rays = options_.sweepRays;
                probeOptions.seed = options_.seed + 7;
                const ProbeSet probes = makeWatertightProbes(MeshTopology::of(scene), probeOptions);
                const std::string offsetLabel = fmt::format("({:g},{:g},{:g})", offsetUnits.x, offsetUnits.y, offsetUnits.z);
                fmt::print(stderr, "  scale {:g} offset {}\n", scale, offsetLabel);
                for (Baseline& baseline : baselines) {
                    const AccelConfig& config = *baseline.config;
                    BuildStats stats;
                    const auto accel = build(config, scene, stats);
                    const TransformCheck check = checkTransformed(*accel, scale, offset, baseRays, baseline.hits,
                                                                  probes.probes, options_.threads);
                    const LeakStats& leaks = check.leaks;
                    const size_t primDiff = check.otherPrimitive, tDiff = check.tNotScaling, compared = check.compared;
                    for (const std::string& e : check.examples) fmt::print(stderr, "    {}\n", e);
                    for (const std::string& e : leaks.examples) fmt::print(stderr, "    {}\n", e);
                    std::optional<double> sahRel;
                    const BuildStats& baseStats = baseline.stats;
                    if (stats.sah && baseStats.sah && offsetUnits == DVec3(0))
                        sahRel = (stats.sah->cost - baseStats.sah->cost) / baseStats.sah->cost;
                    baseline.leaks += leaks.leaks + leaks.occlusionLeaks;
                    baseline.mismatches += primDiff + tDiff;
                    if (!check.passed())
                        fail(config, fmt::format("scale {:g} offset {}: {} leaks, {} any-hit leaks, {} other primitives, "
                                                 "{} t not scaling, of {} probes and {} rays",
                                                 scale, offsetLabel, leaks.leaks, leaks.occlusionLeaks, primDiff, tDiff,
                                                 leaks.rays, compared));
                    if (sahRel && std::abs(*sahRel) > sahScaleTolerance(scale))
                        fail(config, fmt::format("scale {:g}: SAH cost {:.6g} differs from {:.6g} at scale 1 by {:.2e}",
                                                 scale, stats.sah->cost, baseStats.sah->cost, *sahRel));
                    table += fmt::format("{:<14} {:>7g} {:<16} {:>8} {:>6} {:>9} {:>8} {:>10} {:>10}\n", config.label, scale,
                                         offsetLabel, leaks.rays, leaks.leaks + leaks.occlusionLeaks, primDiff, tDiff,
                                         stats.sah ? fmt::format("{:.4f}", stats.sah->cost) : "n/a",
                                         sahRel ? fmt::format("{:.1e}", *sahRel) : "");
                    rows.push_back({{"accel", config.label},
                                    {"scale", scale},
                                    {"offset_in_sizes", {offsetUnits.x, offsetUnits.y, offsetUnits.z}},
                                    {"rays", leaks.rays},
                                    {"leaks", leaks.leaks},
                                    {"any_hit_leaks", leaks.occlusionLeaks},
                                    {"compared_rays", compared},
                                    {"other_primitive", primDiff},
                                    {"t_not_scaling", tDiff},
                                    {"sah", stats.sah ? nlohmann::json(stats.sah->cost) : nlohmann::json()},
                                    {"sah_relative_to_scale_1", sahRel ? nlohmann::json(*sahRel) : nlohmann::json()}});
                }
            }
        for (const Baseline& b : baselines)
            fmt::print(stderr, "  {}: {} leaks, {} mismatches over the sweep\n", b.config->label, b.leaks, b.mismatches);
        results_["sweep"] = rows;
        const std::string section = fmt::format(
            "scale/translation sweep: {} scaled, then moved by offset x its scaled size; leaks include any-hit; "
            "prim/t diff on rays moved with the scene; SAH rel = relative change from scale 1\n",
            base.name);
        fmt::print("{}{}\n", section, table);
    }

    // --- shadow acne ------------------------------------------------------------------------

    void acne() {
        fmt::print(stderr, "== shadow acne: lit planes far from the origin, and grounds z = 0 lit from low\n");
        nlohmann::json rows = nlohmann::json::array();
        std::string table = fmt::format("{:<22} {:<14} {:>8} {:>8} {:>14} {:>6}\n", "plane", "accel", "pixels", "on plane",
                                        "self-shadowed", "dark");
        for (const AcneCase& c : acneCases()) {
            const Scene& scene = c.scene;
            for (const AccelConfig& config : configs_) {
                if (config.name == "naive" && scene.triangleCount() > options_.naiveMaxTriangles) continue;
                BuildStats stats;
                const auto accel = build(config, scene, stats);
                const AcneCheck check = checkShadowAcne(scene, *accel, options_.acnePixels, options_.threads);
                const size_t onPlane = check.onPlane, shadowed = check.selfShadowed, dark = check.dark;
                const size_t pixels = check.pixels;
                if (c.mustPass && !check.passed(c.darkIsFault))
                    fail(config, fmt::format("{}: {} self-shadowed and {} dark of {} plane pixels ({} pixels)", scene.name,
                                             shadowed, dark, onPlane, pixels));
                table += fmt::format("{:<22} {:<14} {:>8} {:>8} {:>14} {:>6}\n", scene.name, config.label, pixels, onPlane,
                                     shadowed, dark);
                rows.push_back({{"plane", scene.name},
                                {"distance", c.distance},
                                {"accel", config.label},
                                {"pixels", pixels},
                                {"on_plane", onPlane},
                                {"self_shadowed", shadowed},
                                {"dark", dark}});
            }
        }
        results_["acne"] = rows;
        const std::string section =
            "shadow acne: planes whose centre is 1e4 (checked) and 1e6 (reported) from the origin, lit from the camera's "
            "side, and grounds z = 0 lit from 5 degrees (self-shadowing checked); self-shadowed = pixel darker with "
            "shadows than without; dark = not above the ambient term\n";
        fmt::print("{}{}\n", section, table);
    }

    // --- builders at the edge ----------------------------------------------------------------

    void builders() {
        const size_t n = options_.builderPrims;
        fmt::print(stderr, "== builders at the edge: {} primitives\n", n);
        nlohmann::json rows = nlohmann::json::array();
        std::string table = fmt::format("{:<18} {:<14} {:>9} {:>10} {:>6} {:>9} {:>9} {:>9}\n", "scene", "accel", "prims",
                                        "build ms", "depth", "nodes", "max leaf", "vs naive");
        for (const NamedSceneFactory& factory : edgeBuildScenes(n, options_.seed)) {
            const Scene scene = factory.make();
            const std::vector<Ray> rays = raysTowardTriangles(scene, 256, options_.seed + 3);
            const std::vector<Hit> reference = naiveAnswers(scene, rays, options_.threads);
            for (const AccelConfig& config : configs_) {
                if (config.name == "naive") continue;
                fmt::print(stderr, "  {} {}: ", scene.name, config.label);
                auto accel = createAccelerator(config.name, configured(config));
                const EdgeBuildCheck check =
                    checkEdgeBuild(*accel, scene, rays, reference, options_.builderMaxSeconds, options_.threads);
                const BuildStats& stats = check.stats;
                const size_t wrong = check.differ;
                fmt::print(stderr, "built in {:.0f} ms, depth {}, {} of {} answers differ from naive\n", stats.buildMs,
                           stats.maxDepth ? fmt::format("{}", *stats.maxDepth) : "n/a", wrong, rays.size());
                for (const std::string& e : check.examples) fmt::print(stderr, "    {}\n", e);
                // What the structure promises, and bounded time and memory of every structure.
                for (const std::string& problem : check.problems) fail(config, fmt::format("{}: {}", scene.name, problem));
                if (wrong) fail(config, fmt::format("{}: {} of {} answers differ from naive", scene.name, wrong, rays.size()));
                auto optional = [](const auto& v) { return v ? fmt::format("{}", *v) : std::string("n/a"); };
                table += fmt::format("{:<18} {:<14} {:>9} {:>10.0f} {:>6} {:>9} {:>9} {:>9}\n", scene.name, config.label,
                                     stats.primitives, stats.buildMs, optional(stats.maxDepth), optional(stats.nodes),
                                     optional(stats.maxLeafPrimitives), fmt::format("{}/{}", wrong, rays.size()));
                rows.push_back({{"scene", scene.name},
                                {"accel", config.label},
                                {"primitives", stats.primitives},
                                {"build_ms", stats.buildMs},
                                {"max_depth", stats.maxDepth ? nlohmann::json(*stats.maxDepth) : nlohmann::json()},
                                {"nodes", stats.nodes ? nlohmann::json(*stats.nodes) : nlohmann::json()},
                                {"max_leaf", stats.maxLeafPrimitives ? nlohmann::json(*stats.maxLeafPrimitives) : nlohmann::json()},
                                {"rays", rays.size()},
                                {"differ_from_naive", wrong}});
            }
        }
        results_["builders"] = rows;
        const std::string section = "builders at the edge: build time, depth (< 64), and 256 rays toward triangles against naive\n";
        fmt::print("{}{}\n", section, table);
    }

    const StressOptions& options_;
    Env env_{programKeys()};
    std::vector<AccelConfig> configs_;
    nlohmann::json results_;
};

}  // namespace

void addStressCommand(CLI::App& app) {
    auto options = std::make_shared<StressOptions>();
    CLI::App* command = app.add_subcommand("stress", "robustness stress suite: watertightness (leaks per million), "
                                                     "scale/translation, shadow acne, builders at the edge");
    addEnvOptions(*command, options->env);
    command->add_option("--rays", options->rays, "watertightness probes per mesh")->capture_default_str();
    command->add_option("--accel", options->accels, "comma-separated NAME or NAME:Key=value:...")->capture_default_str();
    addScenesOption(*command, options->scenes, "meshes icosphere, cube, torus (generated, small and large), ",
                    fmt::format("{}; one that is not there is skipped", fmt::join(options->scenes, ",")));
    command->add_option("--parts", options->parts, "comma-separated parts to run")->capture_default_str();
    command->add_option("--sweep-rays", options->sweepRays, "probes per scale/offset of the sweep")->capture_default_str();
    command->add_option("--builder-prims", options->builderPrims, "primitives of the builders' edge cases")->capture_default_str();
    command->add_option("--builder-max-seconds", options->builderMaxSeconds, "a slower build fails")->capture_default_str();
    command->add_option("--naive-max", options->naiveMaxTriangles, "naive runs only on meshes up to this many triangles")
        ->capture_default_str();
    command->add_option("--acne-pixels", options->acnePixels, "width and height of the shadow-acne renders")
        ->capture_default_str()
        ->check(CLI::Range(1, 4096));
    command->add_option("--threads", options->threads, "threads for tracing and Embree; 0 = all hardware threads")
        ->capture_default_str()
        ->check(CLI::Range(0, 1024));
    command->add_option("--seed", options->seed, "seed of every generated ray and scene")->capture_default_str();
    command->add_option("--out", options->out, "JSON results")->capture_default_str();
    command->callback([options] {
        bool failed = false;
        const int code = runGuarded([&] {
            const auto start = Clock::now();
            std::vector<AccelConfig> configs = parseAccelConfigList(options->accels);
            nameAccelerators(configs, options->env);
            StressRun run(*options, std::move(configs), options->env.load());
            run.run();
            nlohmann::json results = run.results();
            results["seconds"] = secondsSince(start);
            results["run"] = runJson();
            const std::filesystem::path out = prepareOutputFile(options->out);
            std::ofstream(out) << results.dump(2) << "\n";
            for (const auto& f : results["failures"]) fmt::print("FAIL {}\n", f.get<std::string>());
            fmt::print("{}\n", run.failed() ? fmt::format("stress: {} failures", results["failures"].size())
                                            : std::string("stress: all checks passed (Embree's leaks are reported only)"));
            fmt::print(stderr, "wrote {} ({:.0f} s)\n", out.string(), secondsSince(start));
            failed = run.failed();
        });
        if (code != 0) throw CLI::RuntimeError(code);
        if (failed) throw CLI::RuntimeError(1);
    });
}

}  // namespace bvhlab
