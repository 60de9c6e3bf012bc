// `bvhlab tradeoff [--scenes ...] [--out DIR] [--quick] [--builders] [--resume | --fresh]`: run time
// against error for tdbvh, sahbvh with K bins, sweepbvh and embree (see apps/measure/tradeoff.h), or
// with --builders every builder against Embree's three qualities (apps/measure/builders.h). Results are kept
// per configuration in DIR/<scene>/<config>.json with their result key (result_key.h); a run keeps
// those whose key is this run's, so an interrupted run resumes where it stopped, and measures
// again those of a changed program, plugin, setting or scene. Each configuration of a scene is
// measured in a process of its own (apps/runtime/child_job.h): one that crashes, throws or runs
// past --job-timeout is stored as a failed result with its reason, which the tables show and the
// next run measures again, and the others go on.
#include "apps/cli/command_line.h"
#include "apps/cli/commands.h"
#include "apps/measure/builders.h"
#include "apps/measure/failed_config.h"
#include "apps/measure/tradeoff.h"
#include "apps/runtime/app_keys.h"
#include "apps/runtime/atomic_write.h"
#include "apps/runtime/child_job.h"
#include "apps/runtime/comma_list.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/progress.h"
#include "apps/runtime/result_key.h"
#include "apps/runtime/scene_list.h"
#include "framework/config/install_paths.h"
#include "framework/core/error.h"
#include "framework/core/parse_number.h"

#include <fmt/core.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <map>

namespace bvhlab {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

std::vector<int> parseBins(const std::string& text) {
    std::vector<int> bins;
    for (const std::string& item : splitCommaList(text)) {
        int k = 0;
        if (!parseNumber(item, k) || k < 2 || k > 256)
            throw InputError(fmt::format("--bins: '{}' is not a bin count in 2..256", item));
        bins.push_back(k);
    }
    if (bins.empty()) throw InputError("--bins: no bin count given");
    return bins;
}

// The key of a scene's reference image (Embree's), which the scene's folder keeps for its jobs.
json referenceKeyOf(const Env& sceneEnv, const TradeoffSettings& settings) {
    return resultKey("embree", tradeoffSceneEnv(sceneEnv, settings, settings.raySize, settings.raySize),
                     settings.toJson());
}

// The job of a child process, "S:C": configuration C of scene S (indices into the run's lists),
// measured against the scene's inputs prepared here again, the reference image read from the
// scene's folder, where the parent left it. Returns the configuration's result.
json measureConfigJob(const std::string& job, const std::vector<SceneArgument>& scenes,
                      const std::vector<AccelConfig>& configs, const EnvOptions& envOptions,
                      const TradeoffSettings& settings, const std::filesystem::path& dir) {
    size_t s = 0, c = 0;
    const size_t colon = job.find(':');
    if (colon == std::string::npos || !parseNumber(job.substr(0, colon), s) || !parseNumber(job.substr(colon + 1), c) ||
        s >= scenes.size() || c >= configs.size())
        throw InputError(fmt::format("{} {}: not a configuration of a scene of this tradeoff", kChildJobOption, job));
    const std::string& id = scenes[s].id;
    const Env sceneEnv = scenes[s].load(envOptions);
    if (settings.builders)
        return measureBuilderConfig(prepareBuildersScene(id, sceneEnv, settings), configs[c], settings);
    return measureTradeoffConfig(
        prepareTradeoffScene(id, sceneEnv, settings, dir / id, referenceKeyOf(sceneEnv, settings)), configs[c],
        settings);
}

struct TradeoffOptions {
    EnvOptions env;
    std::vector<std::string> scenes;
    std::string out;  // default out/tradeoff, out/builders with --builders
    bool quick = false;
    bool resume = true;
    std::string bins = "2,4,8,16,32,64,128";
    std::string accels;  // empty: all of ours
    TradeoffSettings settings;
    double jobTimeout = 0;
    ChildJob child;
};

void addTradeoffOptions(CLI::App& command, TradeoffOptions& options) {
    addEnvOptions(command, options.env);
    TradeoffSettings& s = options.settings;
    addScenesOption(command, options.scenes, "", "env/scenes.list; --quick: munich and sibenik");
    command.add_option("--out", options.out,
                       "folder of the results: DIR/<scene>/<config>.json, tradeoff.csv, "
                       "image_error.csv, tradeoff.md (--builders: builders.csv, "
                       "builders_summary.csv, builders.md); default out/tradeoff, out/builders");
    command.add_flag("--builders", s.builders,
                     "compare the builders instead: every structure of --accel (default: all of ours) and "
                     "Embree low/medium/high; T_B, SAH, EPO, T_R of primary, shadow and incoherent rays, Pareto "
                     "front, rank correlations");
    command.add_flag("--quick", options.quick,
                     "CI subset: munich and sibenik, 200x200, K 4,16,64, up to 16 spp, reference 64 spp, 2 passes "
                     "(--builders: the same scenes, rays and passes)");
    command.add_flag("--resume,!--fresh", options.resume,
                     "keep results already in DIR whose result key is this run's (program, structure with its settings "
                     "and plugin, scene, measurement settings; the default); --fresh measures everything again");
    command.add_option("--accel", options.accels,
                       "comma-separated NAME or NAME:Key=value:... to measure (default: every structure of ours; a "
                       "bare sahbvh is the K series; Embree is always added as the yardstick)");
    command.add_option("--bins", options.bins, "sahbvh bin counts K")->capture_default_str();
    command
        .add_option("--ray-size", s.raySize,
                    "T_R and mismatch rays: primary rays of an NxN image (0 = the scene's size)")
        ->capture_default_str()
        ->check(CLI::Range(0, 16384));
    command.add_option("--size", s.seriesSize, "images of the spp series and the reference: NxN")
        ->capture_default_str()
        ->check(CLI::Range(1, 16384));
    command.add_option("--max-spp", s.maxSpp, "the series renders 1, 2, 4, ... up to this many samples per pixel")
        ->capture_default_str()
        ->check(CLI::Range(1, 65536));
    command.add_option("--reference-spp", s.referenceSpp, "samples per pixel of the reference image")
        ->capture_default_str()
        ->check(CLI::Range(1, 65536));
    command.add_option("--builds", s.builds, "builds per configuration (median)")
        ->capture_default_str()
        ->check(CLI::Range(1, 100));
    command.add_option("--passes", s.passes, "passes over each ray set (median)")
        ->capture_default_str()
        ->check(CLI::Range(1, 100));
    command
        .add_option("--threads", s.threads, "threads of every timed build, trace and render; 0 = all hardware threads")
        ->capture_default_str()
        ->check(CLI::Range(0, 1024));
    addJobTimeoutOption(command, options.jobTimeout);
    addChildJobOptions(command, options.child);
}

// The settings the options give: --quick's subset, except where an option was given explicitly.
TradeoffSettings tradeoffSettings(const TradeoffOptions& options, const CLI::App& command) {
    TradeoffSettings settings = options.settings;
    std::string bins = options.bins;
    if (options.quick) {
        auto quick = [&](const char* option, auto& field, auto value) {
            if (command.count(option) == 0) field = value;
        };
        quick("--bins", bins, std::string("4,16,64"));
        quick("--ray-size", settings.raySize, 200);
        quick("--size", settings.seriesSize, 200);
        quick("--max-spp", settings.maxSpp, 16);
        quick("--reference-spp", settings.referenceSpp, 64);
        quick("--passes", settings.passes, 2);
        settings.quick = true;
    }
    settings.bins = parseBins(bins);
    if (settings.threads == 0) settings.threads = tbb::info::default_concurrency();
    return settings;
}

std::vector<SceneArgument> tradeoffScenes(const TradeoffOptions& options) {
    std::vector<std::string> sceneArgs = options.scenes;
    if (sceneArgs.empty() && options.quick)
        for (const char* id : {"munich", "sibenik"})
            sceneArgs.push_back(dataFile(std::filesystem::path("env/scenes") / (std::string(id) + ".env")).string());
    return expandSceneList(sceneArgs, options.env);
}

// What a run does with one scene, decided before the first measurement.
struct ScenePlan {
    Env sceneEnv;
    json referenceKey;                       // of Embree's reference image
    std::map<std::string, json> resultKeys;  // by label
    std::vector<AccelConfig> pending;
};

// What the parent process of a run measures, and how far it has come.
struct TradeoffRun {
    const TradeoffOptions& options;
    const TradeoffSettings& settings;
    const std::vector<AccelConfig>& configs;
    const std::vector<SceneArgument>& scenes;
    std::filesystem::path dir;
    Clock::time_point start;
    std::vector<ScenePlan> plans;
    ResumeCount resume;
    size_t measured = 0, failed = 0;

    // Each configuration's result key first: what is kept, what is measured and why, said before
    // the first measurement.
    void planScenes() {
        for (const SceneArgument& scene : scenes) {
            ScenePlan plan{scene.load(options.env), {}, {}, {}};
            const Env tradeoffEnv = tradeoffSceneEnv(plan.sceneEnv, settings, settings.raySize, settings.raySize);
            for (const AccelConfig& config : configs) {
                const json key = plan.resultKeys[config.label] =
                    resultKey(config.name, accelConfigEnv(config, tradeoffEnv), settings.toJson());
                const StoredResult stored =
                    options.resume ? checkStoredResult(dir / scene.id / (labelAsFileName(config.label) + ".json"), key)
                                   : StoredResult{false, "of --fresh"};
                resume.add(stored);
                if (!stored.keep) plan.pending.push_back(config);
            }
            plan.referenceKey = referenceKeyOf(plan.sceneEnv, settings);
            plans.push_back(std::move(plan));
        }
        fmt::print(stderr, "tradeoff: {}\n", resume.summary("configurations", "measure"));
    }

    // Measures one configuration of scene i in a child process and stores its result at once (what
    // a resumed run keeps), or its failure (what it measures again).
    json measureAndStore(size_t i, const AccelConfig& config) {
        const std::string& id = scenes[i].id;
        const auto c = std::find_if(configs.begin(), configs.end(),
                                    [&](const AccelConfig& each) { return each.label == config.label; });
        const JobOutcome outcome = runJobInChild(fmt::format("{}:{}", i, c - configs.begin()), options.jobTimeout);
        json result = outcome.passed() ? outcome.result : failedConfigResult(id, config, outcome.failure());
        if (outcome.passed()) result["result_key"] = plans[i].resultKeys.at(config.label);
        result["measure_s"] = outcome.seconds;
        writeFileAtomically(dir / id / (labelAsFileName(config.label) + ".json"), result.dump(2) + "\n");
        ++measured;
        if (!outcome.passed()) {
            ++failed;
            fmt::print(stderr, "  {} {}: failed: {}\n", id, config.label, outcome.failure());
        }
        return result;
    }

    std::string eta() const {
        const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
        const size_t left = scenes.size() * configs.size() - resume.kept() - measured;
        return fmt::format("{}, {} left, ETA {}", Progress::formatDuration(elapsed), left,
                           Progress::formatDuration(elapsed / double(measured) * double(left)));
    }

    // The scene is prepared here once, so that a scene that cannot be loaded is said once and the
    // reference image is rendered once (each job reads it), then let go while the jobs prepare it
    // again in their processes.
    void measureBuilders(size_t i) {
        const std::string& id = scenes[i].id;
        {
            const BuildersScene scene = prepareBuildersScene(id, plans[i].sceneEnv, settings);
            fmt::print(stderr, "  {}: {} triangles, {} primary, {} shadow and {} incoherent rays\n", id,
                       scene.scene.triangleCount(), scene.rays.primary.size(), scene.rays.shadow.size(),
                       scene.rays.incoherent.size());
        }
        for (const AccelConfig& config : plans[i].pending) {
            const json result = measureAndStore(i, config);
            if (isFailedConfig(result)) continue;
            fmt::print(stderr, "  {} {}: T_B {:.1f} ms, T_R {:.3f}/{:.3f}/{:.3f} us (CPU) ({})\n", id, config.label,
                       result["build_ms"].get<double>(), result["primary"]["t_r_cpu_us"].get<double>(),
                       result["shadow"]["t_r_cpu_us"].get<double>(), result["incoherent"]["t_r_cpu_us"].get<double>(),
                       eta());
        }
    }

    void measureTradeoff(size_t i) {
        const std::string& id = scenes[i].id;
        {
            const TradeoffScene scene =
                prepareTradeoffScene(id, plans[i].sceneEnv, settings, dir / id, plans[i].referenceKey);
            fmt::print(stderr, "  {}: {} triangles, {} primary and {} shadow rays, images {}x{}\n", id,
                       scene.scene.triangleCount(), scene.rays.primary.size(), scene.rays.shadow.size(),
                       scene.seriesCamera.width, scene.seriesCamera.height);
        }
        for (const AccelConfig& config : plans[i].pending) {
            const json result = measureAndStore(i, config);
            if (isFailedConfig(result)) continue;
            fmt::print(stderr,
                       "  {} {}: T_B {:.1f} ms, SAH {}, T_R {:.3f}/{:.3f} us, image {} spp {:.0f} ms (CPU; wall "
                       "{:.0f} ms), mismatches {}/{} ({})\n",
                       id, config.label, result["build_cpu_ms"].get<double>(),
                       result["sah"].is_null() ? "n/a" : fmt::format("{:.2f}", result["sah"].get<double>()),
                       result["primary"]["t_r_cpu_us"].get<double>(), result["shadow"]["t_r_cpu_us"].get<double>(),
                       settings.maxSpp, result["series"].back()["time_to_image_cpu_ms"].get<double>(),
                       result["series"].back()["time_to_image_ms"].get<double>(),
                       result["primary"]["mismatches"].get<size_t>(), result["shadow"]["mismatches"].get<size_t>(),
                       eta());
        }
    }

    // Measures what the plans left pending, scene by scene; a scene with nothing to measure is not
    // even loaded. Returns the ids of the scenes, for the report.
    std::vector<std::string> measureAll() {
        std::vector<std::string> ids;
        Progress progress;
        for (size_t i = 0; i < scenes.size(); ++i) {
            const std::string& id = scenes[i].id;
            ids.push_back(id);
            progress.phase(fmt::format("[scene {}/{}] {}: {} of {} configurations to measure", i + 1, scenes.size(), id,
                                       plans[i].pending.size(), configs.size()));
            if (plans[i].pending.empty()) continue;
            std::filesystem::create_directories(dir / id);
            if (settings.builders)
                measureBuilders(i);
            else
                measureTradeoff(i);
        }
        return ids;
    }
};

// The run the options ask for; returns how many of the configurations it measured failed.
size_t runTradeoff(TradeoffOptions& options, const CLI::App& command) {
    const auto start = Clock::now();
    const TradeoffSettings settings = tradeoffSettings(options, command);
    const std::vector<AccelConfig> configs =
        settings.builders ? builderConfigs(options.accels) : tradeoffConfigs(settings, options.accels);
    nameAccelerators(configs, options.env);
    checkAccelConfigs(configs, options.env.load());
    const std::vector<SceneArgument> scenes = tradeoffScenes(options);
    const std::string out = !options.out.empty() ? options.out : settings.builders ? "out/builders" : "out/tradeoff";
    const std::filesystem::path dir = prepareOutputFolder(out);
    if (options.child.isChild()) {
        options.child.run(
            [&] { return measureConfigJob(options.child.job, scenes, configs, options.env, settings, dir); });
        return 0;
    }

    TradeoffRun run{options, settings, configs, scenes, dir, start, {}, {}};
    run.planScenes();
    const std::vector<std::string> ids = run.measureAll();
    const std::string md = settings.builders ? writeBuildersReport(dir, ids, configs, settings)
                                             : writeTradeoffReport(dir, ids, configs, settings);
    fmt::print("{}", md);
    fmt::print(stderr, "tradeoff: {} configurations measured, {} kept from an earlier run, in {}; wrote {}\n",
               run.measured, run.resume.kept(),
               Progress::formatDuration(std::chrono::duration<double>(Clock::now() - start).count()),
               (dir / (settings.builders ? "builders.csv" : "tradeoff.csv")).string());
    if (run.failed) fmt::print(stderr, "tradeoff: {} of {} configurations measured failed\n", run.failed, run.measured);
    return run.failed;
}

}  // namespace

void addTradeoffCommand(CLI::App& app) {
    auto options = std::make_shared<TradeoffOptions>();
    CLI::App* command = app.add_subcommand(
        "tradeoff",
        "run time against error: build time vs SAH gap, T_R, time to image, image error, mismatches vs Embree");
    addTradeoffOptions(*command, *options);
    command->callback([options, command] { runJobsGuarded([&] { return runTradeoff(*options, *command); }); });
}

}  // namespace bvhlab
