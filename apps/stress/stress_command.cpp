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
// Each part of each structure is a job in a process of its own (apps/runtime/child_job.h): one
// that crashes, throws or runs past --job-timeout is a failed row with its reason, and the rest
// goes on; a build at the edge that outlasts --builder-max-seconds fails its case and ends its job.
// Tables on stdout, JSON in --out, progress on stderr. Exit code 3 when a job failed, else 1 when
// one of our accelerators (not Embree, which is reported only) fails a check.
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
#include "apps/runtime/atomic_write.h"
#include "apps/runtime/build_watch.h"
#include "apps/runtime/child_job.h"
#include "apps/runtime/comma_list.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/program_keys.h"
#include "apps/runtime/run_record.h"
#include "apps/runtime/scene_list.h"
#include "apps/runtime/scene_loading.h"
#include "framework/config/common_keys.h"
#include "framework/core/error.h"
#include "framework/core/parse_number.h"
#include "framework/core/timed_build.h"
#include "framework/render/camera.h"
#include "framework/render/renderer.h"
#include "framework/report/provenance.h"

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <tbb/task_arena.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <fstream>
#include <functional>
#include <mutex>
#include <sstream>
#include <thread>

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
    double jobTimeout = 0;
    ChildJob child;
};

// The parts, in the order they run.
const char* const kParts[] = {"watertight", "sweep", "acne", "builders"};

// Runs `body` on a thread of its own and waits for it at most `seconds`; false when it has not
// returned by then (a build that never ends: the thread is left to the process's end).
bool finishesWithin(double seconds, std::function<void()> body) {
    struct State {
        std::mutex mutex;
        std::condition_variable done;
        bool finished = false;
        std::exception_ptr error;
    };
    auto state = std::make_shared<State>();
    std::thread([state, body = std::move(body)] {
        std::exception_ptr error;
        try {
            body();
        } catch (...) {
            error = std::current_exception();
        }
        const std::lock_guard lock(state->mutex);
        state->finished = true;
        state->error = error;
        state->done.notify_all();
    }).detach();
    std::unique_lock lock(state->mutex);
    if (!state->done.wait_for(lock, std::chrono::duration<double>(seconds), [&] { return state->finished; }))
        return false;
    if (state->error) std::rethrow_exception(state->error);
    return true;
}

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

    // Runs each wanted part of each structure as a job in a child process, then prints each
    // part's table with the rows in the order of its cases, and the structures' order within one.
    void run() {
        const std::vector<std::string> parts = splitCommaList(options_.parts);
        for (const std::string& p : parts)
            if (std::find(std::begin(kParts), std::end(kParts), p) == std::end(kParts))
                throw InputError(
                    fmt::format("--parts: unknown part '{}' (known: watertight, sweep, acne, builders)", p));
        // --scenes looked at here once, not only in the jobs' processes: what is said of them (a
        // scene file without a scene env) goes into this run's JSON.
        if (std::find(parts.begin(), parts.end(), "watertight") != parts.end()) meshes();
        for (const char* part : kParts) {
            if (std::find(parts.begin(), parts.end(), part) == parts.end()) continue;
            fmt::print(stderr, "{}\n", partIntroduction(part));
            struct Entry {
                size_t caseIndex, config;
                nlohmann::json row;
                std::string line;
            };
            std::vector<Entry> entries;
            std::string failedLines;
            nlohmann::json failedRows = nlohmann::json::array();
            for (size_t c = 0; c < configs_.size(); ++c) {
                const AccelConfig& config = configs_[c];
                if (config.name == "naive" && std::string(part) == "builders") continue;
                const JobOutcome outcome = runJobInChild(fmt::format("{}/{}", part, c), options_.jobTimeout);
                if (!outcome.passed()) {
                    // A failed job fails the run, Embree's too: its part has no answer to report.
                    ++failedJobs_;
                    const std::string message =
                        fmt::format("{}: {}: failed: {}", config.label, part, outcome.failure());
                    fmt::print(stderr, "  FAIL {}\n", message);
                    results_["failures"].push_back(message);
                    failedLines += fmt::format("{}: failed: {}\n", config.label, outcome.failure());
                    failedRows.push_back({{"accel", config.label}, {"failed", outcome.failure()}});
                    continue;
                }
                for (const nlohmann::json& e : outcome.result.at("entries"))
                    entries.push_back({e.at("case").get<size_t>(), c, e.at("row"), e.at("line").get<std::string>()});
                for (const nlohmann::json& f : outcome.result.at("failures")) results_["failures"].push_back(f);
                for (const nlohmann::json& skipped : outcome.result.at("skipped"))
                    if (!results_.contains("skipped") ||
                        std::find(results_["skipped"].begin(), results_["skipped"].end(), skipped) ==
                            results_["skipped"].end())
                        results_["skipped"].push_back(skipped);
            }
            std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
                return std::pair(a.caseIndex, a.config) < std::pair(b.caseIndex, b.config);
            });
            nlohmann::json rows = nlohmann::json::array();
            std::string table = partHeader(part);
            for (Entry& e : entries) {
                table += e.line;
                rows.push_back(std::move(e.row));
            }
            for (nlohmann::json& row : failedRows) rows.push_back(std::move(row));
            results_[part] = rows;
            fmt::print("{}{}{}\n", partSection(part), table, failedLines);
        }
        results_["failed_jobs"] = failedJobs_;
    }

    // In a child process: job "PART/CONFIG" of run(), one part of one structure.
    void runChildJob(const ChildJob& child) {
        const size_t slash = child.job.find('/');
        size_t c = 0;
        const std::string part = child.job.substr(0, slash);
        if (slash == std::string::npos || !parseNumber(std::string_view(child.job).substr(slash + 1), c) ||
            c >= configs_.size() || std::find(std::begin(kParts), std::end(kParts), part) == std::end(kParts))
            throw InputError(fmt::format("{} {}: not a job of this stress run", kChildJobOption, child.job));
        configs_ = {configs_[c]};
        child_ = &child;
        child.run([&] {
            if (part == "watertight") watertight();
            if (part == "sweep") sweep();
            if (part == "acne") acne();
            if (part == "builders") builders();
            return childResult();
        });
    }

    const nlohmann::json& results() const { return results_; }
    size_t failedJobs() const { return failedJobs_; }
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
        const BuildWatch watch(fmt::format("{} on {}", config.label, scene.name));
        arena.execute([&] { stats = timedBuild(*accel, scene.primitives()); });
        return accel;
    }

    // What a child hands back: its rows with their case and table line, and what failed.
    nlohmann::json childResult() const {
        return {{"entries", entries_},
                {"failures", results_["failures"]},
                {"skipped", results_.value("skipped", nlohmann::json::array())}};
    }

    // A row of case `caseIndex` of the part (a mesh, a scale and offset, a plane, a scene at the
    // edge) and its line in the part's table.
    void add(size_t caseIndex, nlohmann::json row, std::string line) {
        entries_.push_back({{"case", caseIndex}, {"row", std::move(row)}, {"line", std::move(line)}});
    }

    // The line on stderr before a part, the header of its table and the text above it.
    std::string partIntroduction(const std::string& part) const {
        if (part == "watertight")
            return fmt::format("== watertightness: {} rays per mesh at interior edges and vertices", options_.rays);
        if (part == "sweep") {
            const Scene base = sweepBase();
            return fmt::format(
                "== scale/translation sweep on {} ({} triangles, size {:.3g}): {} scales x {} offsets, {} "
                "probes and {} rays toward triangles each",
                base.name, base.triangleCount(), glm::length(DVec3(base.bounds.diagonal())), sweepScales().size(),
                sweepOffsets().size(), options_.sweepRays, sweepRayCount());
        }
        if (part == "acne") return "== shadow acne: lit planes far from the origin, and grounds z = 0 lit from low";
        return fmt::format("== builders at the edge: {} primitives", options_.builderPrims);
    }
    static std::string partHeader(const std::string& part) {
        if (part == "watertight")
            return fmt::format("{:<16} {:>8} {:<14} {:>9} {:>7} {:>11} {:>9} {:>11} {:>7} {:>9}\n", "mesh", "tris",
                               "accel", "rays", "leaks", "per million", "any-hit", "per million", "batch", "batch any");
        if (part == "sweep")
            return fmt::format("{:<14} {:>7} {:<16} {:>8} {:>6} {:>9} {:>8} {:>10} {:>10}\n", "accel", "scale",
                               "offset/size", "rays", "leaks", "prim diff", "t diff", "SAH", "SAH rel");
        if (part == "acne")
            return fmt::format("{:<22} {:<14} {:>8} {:>8} {:>14} {:>6}\n", "plane", "accel", "pixels", "on plane",
                               "self-shadowed", "dark");
        return fmt::format("{:<18} {:<14} {:>9} {:>10} {:>6} {:>9} {:>9} {:>9}\n", "scene", "accel", "prims",
                           "build ms", "depth", "nodes", "max leaf", "vs naive");
    }
    static std::string partSection(const std::string& part) {
        if (part == "watertight")
            return "watertightness: rays aimed exactly at interior edges and vertices of closed meshes, tmax = 1.0001 "
                   "x "
                   "distance; a leak is a miss (closest hit), any-hit = isOccluded false; batch, batch any = the same "
                   "through findNearestBatch and isOccludedBatch\n";
        if (part == "sweep")
            return fmt::format(
                "scale/translation sweep: {} scaled, then moved by offset x its scaled size; leaks include "
                "any-hit; prim/t diff on rays moved with the scene; SAH rel = relative change from scale 1\n",
                sweepBase().name);
        if (part == "acne")
            return "shadow acne: planes whose centre is 1e4 (checked) and 1e6 (reported) from the origin, lit from the "
                   "camera's side, and grounds z = 0 lit from 5 degrees (self-shadowing checked); self-shadowed = "
                   "pixel "
                   "darker with shadows than without; dark = not above the ambient term\n";
        return "builders at the edge: build time, depth (< 64), and 256 rays toward triangles against naive\n";
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

    // The meshes --scenes names: generated families (small and large variants), or files, each read
    // through its scene's env (an animated one at Scene::frame). One that cannot be had (a file
    // that is not there, a frame past the last) throws InputError when made: it is skipped.
    std::vector<std::function<Scene()>> meshes() const {
        std::vector<std::function<Scene()>> list;
        for (const std::string& argument : options_.scenes)
            for (const std::string& name : splitCommaList(argument)) {
                const std::vector<std::function<Scene()>> family = closedMeshFamily(name);
                list.insert(list.end(), family.begin(), family.end());
                if (!family.empty()) continue;
                // What the other commands' --scenes take.
                std::vector<Env> envs;
                try {
                    for (const SceneArgument& scene : expandSceneList({name}, options_.env))
                        envs.push_back(scene.load(options_.env));
                } catch (const InputError& missing) {
                    list.push_back([missing]() -> Scene { throw missing; });
                    continue;
                }
                for (const Env& env : envs) list.push_back([env] { return loadSceneFor(env); });
            }
        return list;
    }

    void watertight() {
        size_t mesh = 0;
        for (const auto& make : meshes()) {
            const size_t caseIndex = mesh++;
            const auto start = Clock::now();
            std::optional<Scene> scene;
            try {
                scene = make();
            } catch (const InputError& e) {
                fmt::print(stderr, "skipping: {}\n", e.what());
                results_["skipped"].push_back(fmt::format("watertight: {}", e.what()));
                continue;
            }
            const MeshTopology topology = MeshTopology::of(*scene);
            ProbeOptions probeOptions;
            probeOptions.rays = options_.rays;
            probeOptions.seed = options_.seed;
            const ProbeSet probes = makeWatertightProbes(topology, probeOptions);
            fmt::print(stderr, "{}: {}; {} probes ({} of {} candidate points rejected) in {:.1f} s\n", scene->name,
                       topology.summary(), probes.probes.size(), probes.rejected, probes.candidates,
                       secondsSince(start));
            for (const AccelConfig& config : configs_) {
                if (config.name == "naive" && scene->triangleCount() > options_.naiveMaxTriangles) continue;
                BuildStats stats;
                const auto accel = build(config, *scene, stats);
                const auto traced = Clock::now();
                const LeakStats leaks = countLeaks(*accel, probes.probes, options_.threads);
                fmt::print(
                    stderr,
                    "  {}: built in {:.0f} ms, {} leaks, {} any-hit leaks (batch: {}, {}) of {} rays in {:.1f} s\n",
                    config.label, stats.buildMs, leaks.leaks, leaks.occlusionLeaks, leaks.batchLeaks,
                    leaks.batchOcclusionLeaks, leaks.rays, secondsSince(traced));
                for (const std::string& e : leaks.examples) fmt::print(stderr, "    {}\n", e);
                if (leaks.leaks || leaks.occlusionLeaks || leaks.batchLeaks || leaks.batchOcclusionLeaks)
                    fail(config,
                         fmt::format("{} leaks and {} any-hit leaks (batch queries: {} and {}) in {} rays through {}",
                                     leaks.leaks, leaks.occlusionLeaks, leaks.batchLeaks, leaks.batchOcclusionLeaks,
                                     leaks.rays, scene->name));
                add(caseIndex,
                    {{"mesh", scene->name},
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
                     {"examples", leaks.examples}},
                    fmt::format("{:<16} {:>8} {:<14} {:>9} {:>7} {:>11.1f} {:>9} {:>11.1f} {:>7} {:>9}\n", scene->name,
                                scene->triangleCount(), config.label, leaks.rays, leaks.leaks, leaks.perMillion(),
                                leaks.occlusionLeaks, leaks.occlusionPerMillion(), leaks.batchLeaks,
                                leaks.batchOcclusionLeaks));
            }
        }
    }

    // --- scale and translation --------------------------------------------------------------

    static Scene sweepBase() { return makeClosedTrioScene(4, 16, 64, 32); }
    size_t sweepRayCount() const { return std::max<size_t>(options_.sweepRays / 5, 1000); }

    void sweep() {
        const Scene base = sweepBase();
        const double size = glm::length(DVec3(base.bounds.diagonal()));
        const std::vector<double> scales = sweepScales();
        const std::vector<DVec3> offsets = sweepOffsets();
        const std::vector<Ray> baseRays = raysTowardTriangles(base, sweepRayCount(), options_.seed);
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
            accel->findNearestBatch(baseRays, b.hits, counters, {}, RayCoherence::Incoherent);
            baselines.push_back(std::move(b));
        }
        size_t caseIndex = 0;
        for (double scale : scales)
            for (const DVec3& offsetUnits : offsets) {
                ++caseIndex;
                const DVec3 offset = offsetUnits * size * scale;
                const Scene scene = transformedScene(base, scale, offset);
                ProbeOptions probeOptions;
                probeOptions.rays = options_.sweepRays;
                probeOptions.seed = options_.seed + 7;
                const ProbeSet probes = makeWatertightProbes(MeshTopology::of(scene), probeOptions);
                const std::string offsetLabel =
                    fmt::format("({:g},{:g},{:g})", offsetUnits.x, offsetUnits.y, offsetUnits.z);
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
                        fail(config,
                             fmt::format("scale {:g} offset {}: {} leaks, {} any-hit leaks, {} other primitives, "
                                         "{} t not scaling, of {} probes and {} rays",
                                         scale, offsetLabel, leaks.leaks, leaks.occlusionLeaks, primDiff, tDiff,
                                         leaks.rays, compared));
                    if (sahRel && std::abs(*sahRel) > sahScaleTolerance(scale))
                        fail(config, fmt::format("scale {:g}: SAH cost {:.6g} differs from {:.6g} at scale 1 by {:.2e}",
                                                 scale, stats.sah->cost, baseStats.sah->cost, *sahRel));
                    add(caseIndex,
                        {{"accel", config.label},
                         {"scale", scale},
                         {"offset_in_sizes", {offsetUnits.x, offsetUnits.y, offsetUnits.z}},
                         {"rays", leaks.rays},
                         {"leaks", leaks.leaks},
                         {"any_hit_leaks", leaks.occlusionLeaks},
                         {"compared_rays", compared},
                         {"other_primitive", primDiff},
                         {"t_not_scaling", tDiff},
                         {"sah", stats.sah ? nlohmann::json(stats.sah->cost) : nlohmann::json()},
                         {"sah_relative_to_scale_1", sahRel ? nlohmann::json(*sahRel) : nlohmann::json()}},
                        fmt::format("{:<14} {:>7g} {:<16} {:>8} {:>6} {:>9} {:>8} {:>10} {:>10}\n", config.label, scale,
                                    offsetLabel, leaks.rays, leaks.leaks + leaks.occlusionLeaks, primDiff, tDiff,
                                    stats.sah ? fmt::format("{:.4f}", stats.sah->cost) : "n/a",
                                    sahRel ? fmt::format("{:.1e}", *sahRel) : ""));
                }
            }
        for (const Baseline& b : baselines)
            fmt::print(stderr, "  {}: {} leaks, {} mismatches over the sweep\n", b.config->label, b.leaks,
                       b.mismatches);
    }

    // --- shadow acne ------------------------------------------------------------------------

    void acne() {
        size_t caseIndex = 0;
        for (const AcneCase& c : acneCases()) {
            ++caseIndex;
            const Scene& scene = c.scene;
            for (const AccelConfig& config : configs_) {
                if (config.name == "naive" && scene.triangleCount() > options_.naiveMaxTriangles) continue;
                BuildStats stats;
                const auto accel = build(config, scene, stats);
                const AcneCheck check = checkShadowAcne(scene, *accel, options_.acnePixels, options_.threads);
                const size_t onPlane = check.onPlane, shadowed = check.selfShadowed, dark = check.dark;
                const size_t pixels = check.pixels;
                if (c.mustPass && !check.passed(c.darkIsFault))
                    fail(config, fmt::format("{}: {} self-shadowed and {} dark of {} plane pixels ({} pixels)",
                                             scene.name, shadowed, dark, onPlane, pixels));
                add(caseIndex,
                    {{"plane", scene.name},
                     {"distance", c.distance},
                     {"accel", config.label},
                     {"pixels", pixels},
                     {"on_plane", onPlane},
                     {"self_shadowed", shadowed},
                     {"dark", dark}},
                    fmt::format("{:<22} {:<14} {:>8} {:>8} {:>14} {:>6}\n", scene.name, config.label, pixels, onPlane,
                                shadowed, dark));
            }
        }
    }

    // --- builders at the edge ----------------------------------------------------------------

    // A build that has not ended after --builder-max-seconds fails its case; as it cannot be
    // stopped, the job ends there with the rows it has (the structure's later cases do not run).
    void builders() {
        size_t caseIndex = 0;
        for (const NamedSceneFactory& factory : edgeBuildScenes(options_.builderPrims, options_.seed)) {
            ++caseIndex;
            const Scene scene = factory.make();
            const std::vector<Ray> rays = raysTowardTriangles(scene, 256, options_.seed + 3);
            const std::vector<Hit> reference = naiveAnswers(scene, rays, options_.threads);
            for (const AccelConfig& config : configs_) {
                if (config.name == "naive") continue;
                fmt::print(stderr, "  {} {}: ", scene.name, config.label);
                auto accel = createAccelerator(config.name, configured(config));
                EdgeBuildCheck check;
                const BuildWatch watch(fmt::format("{} on {}", config.label, scene.name));
                if (!finishesWithin(options_.builderMaxSeconds, [&] {
                        check = checkEdgeBuild(*accel, scene, rays, reference, options_.builderMaxSeconds,
                                               options_.threads);
                    })) {
                    const std::string late = fmt::format(
                        "the build did not end within {:g} s (--builder-max-seconds); "
                        "its later cases were not run",
                        options_.builderMaxSeconds);
                    fmt::print(stderr, "{}\n", late);
                    fail(config, fmt::format("{}: {}", scene.name, late));
                    add(caseIndex, {{"scene", scene.name}, {"accel", config.label}, {"failed", late}},
                        fmt::format("{:<18} {:<14} failed: {}\n", scene.name, config.label, late));
                    child_->finish(childResult());
                }
                const BuildStats& stats = check.stats;
                const size_t wrong = check.differ;
                fmt::print(stderr, "built in {:.0f} ms, depth {}, {} of {} answers differ from naive\n", stats.buildMs,
                           stats.maxDepth ? fmt::format("{}", *stats.maxDepth) : "n/a", wrong, rays.size());
                for (const std::string& e : check.examples) fmt::print(stderr, "    {}\n", e);
                // What the structure promises, and bounded time and memory of every structure.
                for (const std::string& problem : check.problems)
                    fail(config, fmt::format("{}: {}", scene.name, problem));
                if (wrong)
                    fail(config, fmt::format("{}: {} of {} answers differ from naive", scene.name, wrong, rays.size()));
                auto optional = [](const auto& v) { return v ? fmt::format("{}", *v) : std::string("n/a"); };
                add(caseIndex,
                    {{"scene", scene.name},
                     {"accel", config.label},
                     {"primitives", stats.primitives},
                     {"build_ms", stats.buildMs},
                     {"max_depth", stats.maxDepth ? nlohmann::json(*stats.maxDepth) : nlohmann::json()},
                     {"nodes", stats.nodes ? nlohmann::json(*stats.nodes) : nlohmann::json()},
                     {"max_leaf",
                      stats.maxLeafPrimitives ? nlohmann::json(*stats.maxLeafPrimitives) : nlohmann::json()},
                     {"rays", rays.size()},
                     {"differ_from_naive", wrong}},
                    fmt::format("{:<18} {:<14} {:>9} {:>10.0f} {:>6} {:>9} {:>9} {:>9}\n", scene.name, config.label,
                                stats.primitives, stats.buildMs, optional(stats.maxDepth), optional(stats.nodes),
                                optional(stats.maxLeafPrimitives), fmt::format("{}/{}", wrong, rays.size())));
            }
        }
    }

    const StressOptions& options_;
    Env env_{programKeys()};
    std::vector<AccelConfig> configs_;
    nlohmann::json results_;
    nlohmann::json entries_ = nlohmann::json::array();  // a child's rows (add())
    const ChildJob* child_ = nullptr;                   // set in a child process
    size_t failedJobs_ = 0;
};

}  // namespace

void addStressCommand(CLI::App& app) {
    auto options = std::make_shared<StressOptions>();
    CLI::App* command = app.add_subcommand("stress",
                                           "robustness stress suite: watertightness (leaks per million), "
                                           "scale/translation, shadow acne, builders at the edge");
    addEnvOptions(*command, options->env);
    command->add_option("--rays", options->rays, "watertightness probes per mesh")->capture_default_str();
    command->add_option("--accel", options->accels, "comma-separated NAME or NAME:Key=value:...")
        ->capture_default_str();
    addScenesOption(*command, options->scenes, "meshes icosphere, cube, torus (generated, small and large), ",
                    fmt::format("{}; one that is not there is skipped", fmt::join(options->scenes, ",")));
    command->add_option("--parts", options->parts, "comma-separated parts to run")->capture_default_str();
    command->add_option("--sweep-rays", options->sweepRays, "probes per scale/offset of the sweep")
        ->capture_default_str();
    command->add_option("--builder-prims", options->builderPrims, "primitives of the builders' edge cases")
        ->capture_default_str();
    command->add_option("--builder-max-seconds", options->builderMaxSeconds, "a slower build fails")
        ->capture_default_str();
    command
        ->add_option("--naive-max", options->naiveMaxTriangles, "naive runs only on meshes up to this many triangles")
        ->capture_default_str();
    command->add_option("--acne-pixels", options->acnePixels, "width and height of the shadow-acne renders")
        ->capture_default_str()
        ->check(CLI::Range(1, 4096));
    command->add_option("--threads", options->threads, "threads for tracing and Embree; 0 = all hardware threads")
        ->capture_default_str()
        ->check(CLI::Range(0, 1024));
    command->add_option("--seed", options->seed, "seed of every generated ray and scene")->capture_default_str();
    command->add_option("--out", options->out, "JSON results")->capture_default_str();
    addJobTimeoutOption(*command, options->jobTimeout);
    addChildJobOptions(*command, options->child);
    command->callback([options] {
        int failedCode = 0;
        const int code = runGuarded([&] {
            const auto start = Clock::now();
            std::vector<AccelConfig> configs = parseAccelConfigList(options->accels);
            nameAccelerators(configs, options->env);
            StressRun run(*options, std::move(configs), options->env.load());
            if (options->child.isChild()) return run.runChildJob(options->child);
            run.run();
            nlohmann::json results = run.results();
            results["seconds"] = secondsSince(start);
            results["run"] = runJson();
            const std::filesystem::path out = prepareOutputFile(options->out);
            std::ofstream(out) << results.dump(2) << "\n";
            for (const auto& f : results["failures"]) fmt::print("FAIL {}\n", f.get<std::string>());
            const nlohmann::json skipped = results.value("skipped", nlohmann::json::array());
            for (const auto& s : skipped) fmt::print("SKIP {}\n", s.get<std::string>());
            fmt::print("{}{}\n",
                       run.failed()
                           ? fmt::format("stress: {} failures{}", results["failures"].size(),
                                         run.failedJobs() ? fmt::format(" ({} jobs failed)", run.failedJobs()) : "")
                           : std::string("stress: all checks passed (Embree's leaks are reported only)"),
                       skipped.empty() ? "" : fmt::format(", {} skipped", skipped.size()));
            fmt::print(stderr, "wrote {} ({:.0f} s)\n", out.string(), secondsSince(start));
            failedCode = run.failedJobs() ? kSomeJobsFailedExitCode : run.failed() ? 1 : 0;
        });
        if (code != 0) throw CLI::RuntimeError(code);
        if (failedCode) throw CLI::RuntimeError(failedCode);
    });
}

}  // namespace bvhlab
