// `bvhlab batch`: the report's Table 1 side by side. For each scene x accelerator (a job): load
// the scene (through the scene cache), build once, render without and with shadows, write the
// images and DIR/jobs/SCENE__ACCEL.json; then make the tables and the contact sheet from the
// jobs of the folder's one batch (DIR/batch.json; a folder holding another batch is refused).
// Each job runs in a process of its own (apps/runtime/child_job.h): one that crashes, throws or
// runs longer than --job-timeout is a failed job, with its reason in the tables, and the batch
// goes on. A rerun keeps each job finished with the result key it would be run with
// (batch_resume.h). `--shard i/n` runs every n-th job; `--merge DIR...` joins the shards of one
// batch; `--slurm N` submits the batch to Slurm as N shards and their merge (slurm_submission.h).
#include "accel/registry.h"
#include "apps/animate/animation_run.h"
#include "apps/batch/batch_resume.h"
#include "apps/batch/batch_settings.h"
#include "apps/batch/batch_table.h"
#include "apps/batch/slurm_submission.h"
#include "apps/cli/command_line.h"
#include "apps/cli/commands.h"
#include "apps/runtime/accel_config.h"
#include "apps/runtime/app_keys.h"
#include "apps/runtime/atomic_write.h"
#include "apps/runtime/build_accelerator.h"
#include "apps/runtime/child_job.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/progress.h"
#include "apps/runtime/render_with_progress.h"
#include "apps/runtime/result_key.h"
#include "apps/runtime/run_record.h"
#include "apps/runtime/scene_list.h"
#include "apps/runtime/scene_loading.h"
#include "framework/config/common_keys.h"
#include "framework/core/error.h"
#include "framework/core/parse_number.h"
#include "framework/io/heatmap.h"
#include "framework/io/image_io.h"
#include "framework/render/camera.h"
#include "framework/render/renderer.h"
#include "framework/report/provenance.h"
#include "framework/report/statistics.h"
#include "framework/scene/scene_loader.h"

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace bvhlab {
namespace {

using nlohmann::json;

struct Shard {
    int index = 0, count = 1;
};

// "i/n" with 0 <= i < n, i 0-based as $SLURM_ARRAY_TASK_ID.
Shard parseShard(const std::string& text) {
    const size_t slash = text.find('/');
    Shard s;
    const std::string_view view = text;
    if (slash == std::string::npos || !parseNumber(view.substr(0, slash), s.index) ||
        !parseNumber(view.substr(slash + 1), s.count) || s.count < 1 || s.index < 0 || s.index >= s.count)
        throw InputError(
            fmt::format("--shard {}: expected i/n with n >= 1 and 0 <= i < n (i is 0-based, as "
                        "$SLURM_ARRAY_TASK_ID), e.g. --shard 0/10",
                        text));
    return s;
}

// --accel: NAME or NAME:Key=value:... configs, each once; their plugins are found by name.
std::vector<AccelConfig> parseBatchAccelerators(const std::string& text, EnvOptions& env) {
    std::vector<AccelConfig> configs = parseAccelConfigList(text);
    for (auto c = configs.begin(); c != configs.end(); ++c)
        if (std::any_of(configs.begin(), c, [&](const AccelConfig& earlier) { return earlier.label == c->label; }))
            throw InputError(fmt::format("--accel: '{}' is listed twice", c->label));
    nameAccelerators(configs, env);
    checkAccelConfigs(configs, env.load());
    return configs;
}

struct Options {
    EnvOptions env;
    std::vector<std::string> scenes;
    std::string accels = "tdbvh,sahbvh,embree";
    std::string out = "out/batch";
    std::string shard;
    bool shardGiven = false;
    std::vector<std::string> merge;
    bool fresh = false;  // delete the folder's batch first
    int slurm = 0;       // --slurm N: submit N shards and their merge; 0: run here
    std::string slurmArgs;
    double jobTimeout = 0;  // seconds; 0: none
    ChildJob child;         // set in the process that runs one job
};

// A job's render (and Embree build) threads: --threads, else its scene's Batch::threads (the
// report's single render thread by default).
int renderThreads(const Options& options, const Env& sceneEnv) {
    return options.env.threads >= 0 ? options.env.threads : sceneEnv.get(keys::Batch::threads);
}

// The env a job runs with: its scene's, its accelerator's overrides, ASDS::type and the render threads.
Env jobEnv(const Options& options, const Env& sceneEnv, const AccelConfig& config) {
    Env env = accelConfigEnv(config, sceneEnv);
    env.set(keys::ASDS::type, config.name, "bvhlab batch --accel");
    env.set(keys::SetRayTracing::threads, std::to_string(renderThreads(options, env)),
            options.env.threads >= 0 ? "--threads" : "Batch::threads");
    return env;
}

// What a job's result depends on (result_key.h): batch renders without and with shadows, or
// measures an animation (its frames and policy are keys of the env).
nlohmann::json jobResultKey(const AccelConfig& config, const Env& env, bool animated) {
    if (animated) return resultKey(config.name, env, {{"command", "batch"}, {"animation", {{"rounds", 1}}}});
    return resultKey(config.name, env, {{"command", "batch"}, {"renders", {"no_shadows", "shadows"}}});
}

// What a batch runs: its scenes with their layered envs, the accelerators, and its settings.
struct BatchPlan {
    std::vector<SceneArgument> scenes;
    std::vector<Env> sceneEnvs;
    std::vector<bool> animated;  // per scene: run as an animation (Batch::animate), not rendered
    std::vector<AccelConfig> accels;
    BatchSettings settings;
};

// A job of the batch: the index-th in table order (scene by scene, an accelerator each), run by a shard.
struct BatchJob {
    const BatchPlan& plan;
    size_t index = 0;
    Shard shard;

    size_t sceneIndex() const { return index / plan.accels.size(); }
    size_t accelIndex() const { return index % plan.accels.size(); }
    const SceneArgument& scene() const { return plan.scenes[sceneIndex()]; }
    const Env& sceneEnv() const { return plan.sceneEnvs[sceneIndex()]; }
    const AccelConfig& accel() const { return plan.accels[accelIndex()]; }
    bool animated() const { return plan.animated[sceneIndex()]; }
    std::string name() const { return batchJobName(scene().id, accel().label); }
    // Its place in the batch, as its job file records it.
    json order() const {
        return {{"scene", sceneIndex()},
                {"accel", accelIndex()},
                {"job", index},
                {"jobs", plan.scenes.size() * plan.accels.size()}};
    }
    std::string shardName() const { return fmt::format("{}/{}", shard.index, shard.count); }
};

// A job's framebuffer step counts, kept until the scene's heat maps are drawn at one scale.
struct FinishedJob {
    nlohmann::json job;
    bool hasCounters = false;
    int width = 0, height = 0;
    std::vector<float> steps[2];  // traversal steps without and with shadows
};

// What a job's process hands back: the job record and the steps for the scene's heat maps.
json finishedJobJson(const FinishedJob& f) {
    return {{"job", f.job},
            {"has_counters", f.hasCounters},
            {"width", f.width},
            {"height", f.height},
            {"steps", {f.steps[0], f.steps[1]}}};
}

FinishedJob finishedJobFromJson(const json& j) {
    FinishedJob f{
        j.at("job"), j.at("has_counters").get<bool>(), j.at("width").get<int>(), j.at("height").get<int>(), {}};
    for (const bool shadows : {false, true}) f.steps[shadows] = j.at("steps").at(shadows).get<std::vector<float>>();
    return f;
}

// One job: build once, render without and with shadows, write images and the job file.
// `scene` is the job's scene loaded as `loadInfo` says; `jobLabel` names the job in its progress.
FinishedJob runJob(const Options& options, const BatchJob& job, const Scene& scene, const SceneLoadInfo& loadInfo,
                   Progress& progress, const std::string& jobLabel) {
    const std::filesystem::path out = options.out;
    const SceneArgument& entry = job.scene();
    const AccelConfig& config = job.accel();
    const std::string& accel = config.label;
    const std::string name = job.name();
    const std::string label = fmt::format("{} {} {}", jobLabel, entry.id, accel);

    const Env env = jobEnv(options, job.sceneEnv(), config);
    const int threads = env.get(keys::SetRayTracing::threads);

    progress.phase(label + ": building");
    tbb::task_arena arena(threads > 0 ? threads : tbb::info::default_concurrency());
    BuiltAccelerator built;
    arena.execute([&] { built = buildAccelerator(scene, env); });

    const Camera camera(resolveCamera(scene, env));
    const RenderSettings settings = RenderSettings::fromEnv(env, scene, camera.spec());
    FinishedJob finished{json(), built.accel->hasCounters(), camera.width(), camera.height(), {}};
    json runs = json::object();
    for (const bool shadows : {false, true}) {
        RenderSettings s = settings;
        s.shadows = shadows;
        Framebuffer fb(camera.width(), camera.height());
        const RenderStats stats =
            renderWithProgress(scene, *built.accel, camera, s, fb, progress,
                               label + (shadows ? ": rendering with shadows" : ": rendering without shadows"));

        // Images: the PNG always (the contact sheet is made from it), EXR as Output:: says; the heat
        // map after the scene's last job (writeSceneHeatmaps).
        const std::string base = "images/" + name + (shadows ? "_shadows" : "");
        json images = {{"png", base + ".png"}};
        writePng(out / (base + ".png"), fb);
        if (env.get(keys::Output::exr)) writeExr(out / (base + ".exr"), fb), images["exr"] = base + ".exr";
        if (env.get(keys::Output::heatmap)) finished.steps[shadows] = std::move(fb.traversalSteps);

        const StatsRow row{scene.name,  accel, scene.primitiveCount(), scene.report, built.accel->hasCounters(),
                           built.stats, stats};
        json run = statsJson(row);
        run["shadows"] = shadows;
        run["images"] = images;
        runs[shadows ? "shadows" : "no_shadows"] = run;
    }

    json record = {
        {"format", "bvhlab-batch-job-1"},
        {"job", name},
        {"scene", entry.id},
        {"settings", job.plan.settings.scene(entry.id)->hash},  // the key the tables check
        {"batch", job.plan.settings.hash},
        {"scene_name", scene.name},
        {"scene_env",
         entry.envFile.empty() ? json() : json(std::filesystem::absolute(entry.envFile).lexically_normal().string())},
        {"scene_file", scene.source.string()},
        {"scene_from_cache", loadInfo.fromCache},
        {"scene_cache_file", loadInfo.cacheFile.string()},
        {"scene_load_ms", loadInfo.ms},
        {"accel", accel},
        {"build_shared", true},  // one build served both renders
        {"order", job.order()},
        {"shard", job.shardName()},
        {"threads", threads},
        {"image", {{"width", camera.width()}, {"height", camera.height()}, {"samples", settings.samples}}},
        {"runs", runs},
        {"env", env.toJson()},
        {"result_key", jobResultKey(config, env, false)},
        {"run", runJson()},
        {"provenance", provenanceJson()}};
    writeFileAtomically(out / "jobs" / (name + ".json"), record.dump(2) + "\n");
    finished.job = std::move(record);
    return finished;
}

// An animated scene's job: the animation over Animate::frames under the job's Animate::policy,
// each frame's update and its camera's primary and shadow rays measured as `bvhlab animate`
// measures a contender (animation_run.h, one round); the job file holds the contender's record.
// A contender that fails fails the job; one that cannot run its policy is kept, skipped.
FinishedJob runAnimationJob(const Options& options, const BatchJob& job, Progress& progress,
                            const std::string& jobLabel) {
    const SceneArgument& entry = job.scene();
    const AccelConfig& config = job.accel();
    const Env env = jobEnv(options, job.sceneEnv(), config);
    int threads = env.get(keys::SetRayTracing::threads);
    if (threads == 0) threads = tbb::info::default_concurrency();

    progress.phase(fmt::format("{} {} {}: loading the animation", jobLabel, entry.id, config.label));
    const auto start = Progress::Clock::now();
    AnimatedScene animated = loadAnimatedSceneFor(job.sceneEnv());
    const double loadMs = std::chrono::duration<double, std::milli>(Progress::Clock::now() - start).count();
    progress.finish();
    const std::filesystem::path file = sceneFileOf(job.sceneEnv());
    AnimationRun measure(
        animated, job.sceneEnv(),
        {parseFrames(env.get(keys::Animate::frames), animated.frameCount, std::string(keys::Animate::frames.name())), 1,
         false, threads});
    measure.addContender(config, env.get(keys::Animate::policy));
    measure.run({});
    const CameraSpec camera = resolveCamera(animated.scene, job.sceneEnv());  // the rays' image, at the last frame
    nlohmann::json contender = measure.contenders().front();
    if (contender.contains("failed")) throw std::runtime_error(contender.at("failed").get<std::string>());
    contender["label"] = config.label;  // one policy per job: the table names the structure

    json record = {
        {"format", "bvhlab-batch-job-1"},
        {"job", job.name()},
        {"scene", entry.id},
        {"settings", job.plan.settings.scene(entry.id)->hash},
        {"batch", job.plan.settings.hash},
        {"scene_name", animated.scene.name},
        {"scene_env",
         entry.envFile.empty() ? json() : json(std::filesystem::absolute(entry.envFile).lexically_normal().string())},
        {"scene_file", file.string()},
        {"scene_load_ms", loadMs},
        {"accel", config.label},
        {"animated", true},
        {"order", job.order()},
        {"shard", job.shardName()},
        {"threads", threads},
        {"image", {{"width", camera.width}, {"height", camera.height}}},
        {"animation", measure.header(file)},
        {"contender", contender},
        {"env", env.toJson()},
        {"result_key", jobResultKey(config, env, true)},
        {"run", runJson()},
        {"provenance", provenanceJson()}};
    writeFileAtomically(std::filesystem::path(options.out) / "jobs" / (job.name() + ".json"), record.dump(2) + "\n");
    return FinishedJob{std::move(record), false, 0, 0, {}};
}

// The job file of a job that failed: what ran (its result key, which a rerun does not keep: the
// job failed) and why it left no results; the tables show it as a failed row.
json failedJobRecord(const BatchJob& job, const json& resultKey, const JobOutcome& outcome) {
    return {{"format", "bvhlab-batch-job-1"},
            {"job", job.name()},
            {"scene", job.scene().id},
            {"settings", job.plan.settings.scene(job.scene().id)->hash},
            {"batch", job.plan.settings.hash},
            {"accel", job.accel().label},
            {"animated", job.animated()},
            {"order", job.order()},
            {"shard", job.shardName()},
            {"failed", outcome.failure()},
            {"result_key", resultKey},
            {"seconds", outcome.seconds},
            {"run", runJson()},
            {"provenance", provenanceJson()}};
}

// The scene's heat maps at one full scale, so that colours compare across its accelerators:
// Output::heatmapScale when set, else that of its jobs kept from an earlier run (batch_resume.h),
// else the largest 99th percentile of its renders in this run (every accelerator with counters,
// without and with shadows). A structure without counters gets none. Then the job files are
// written again with the heat maps' records.
void writeSceneHeatmaps(const std::filesystem::path& out, const std::string& sceneId, std::vector<FinishedJob>& jobs,
                        float fixedScale, const std::optional<HeatmapScale>& keptScale) {
    float largest = 1.0f;
    std::vector<std::string> counted, uncounted;
    for (const FinishedJob& f : jobs) {
        (f.hasCounters ? counted : uncounted).push_back(f.job.at("accel").get<std::string>());
        if (f.hasCounters)
            for (const std::vector<float>& steps : f.steps) largest = std::max(largest, heatmapPercentile99(steps));
    }
    const HeatmapScale scale =
        fixedScale <= 0 && keptScale
            ? *keptScale
            : chooseHeatmapScale(fixedScale, largest,
                                 fmt::format("largest 99th percentile of the scene's renders in this run: {}",
                                             fmt::join(counted, ", ")));
    for (FinishedJob& f : jobs) {
        const std::string name = f.job.at("job").get<std::string>(), accel = f.job.at("accel").get<std::string>();
        for (const bool shadows : {false, true}) {
            json& run = f.job["runs"][shadows ? "shadows" : "no_shadows"];
            const std::string file = "images/" + name + (shadows ? "_shadows" : "") + ".heatmap.png";
            run["heatmap"] =
                writeHeatmap(out / file, file, f.steps[shadows], f.width, f.height, f.hasCounters, accel, scale);
            if (f.hasCounters) run["images"]["heatmap"] = file;
        }
        writeFileAtomically(out / "jobs" / (name + ".json"), f.job.dump(2) + "\n");
    }
    if (!counted.empty())
        fmt::print(stderr, "heat maps of {}: full scale {} traversal steps ({})\n", sceneId, scale.steps, scale.from);
    for (const std::string& accel : uncounted)
        fmt::print(stderr, "heat maps of {}: none for {}: it counts no traversal steps\n", sceneId, accel);
}

// Copies, replacing `to` (a copy, not a link: a shard folder rerun later must not change the merge).
void copyInto(const std::filesystem::path& from, const std::filesystem::path& to) {
    std::error_code ec;
    if (std::filesystem::exists(to) && std::filesystem::equivalent(from, to, ec)) return;  // merging into a shard
    std::filesystem::copy_file(from, to, std::filesystem::copy_options::overwrite_existing);
}

// Makes `out` the folder of the batch `settings`: cleared first with --fresh, refused if it holds
// jobs of another batch, then its settings recorded (before any job, so an interrupted run is
// resumed by the same command).
void prepareFolder(const std::filesystem::path& out, const BatchSettings& settings, bool fresh) {
    if (fresh) clearBatchFolder(out);
    checkBatchFolder(out, settings);
    std::filesystem::create_directories(out / "jobs");
    std::filesystem::create_directories(out / "images");
    writeBatchSettings(out, settings);
}

// Copies the job files and their images of every shard folder into `out`; the shards must be of
// one batch.
void mergeShards(const std::vector<std::string>& dirs, const std::filesystem::path& out, bool fresh) {
    std::optional<BatchSettings> batch;
    for (const std::filesystem::path dir : dirs) {
        if (!std::filesystem::is_directory(dir / "jobs"))
            throw InputError(
                fmt::format("--merge {}: no jobs/ folder here (not the output of bvhlab batch)", dir.string()));
        const std::optional<BatchSettings> settings = readBatchSettings(dir);
        if (!settings)
            throw InputError(
                fmt::format("--merge {}: no batch.json (written by an older bvhlab): the settings of its "
                            "jobs are unknown, so they cannot be merged with others; run that shard again",
                            dir.string()));
        if (batch && settings->hash != batch->hash)
            throw InputError(
                fmt::format("--merge: {} and {} hold shards of different batches ({} -> {}):\n  {}\nmerge "
                            "only the shards of one batch (run with the same --env, -D, --accel and --scenes)",
                            dirs.front(), dir.string(), dirs.front(), dir.string(),
                            fmt::join(batchDifferences(*batch, *settings), "\n  ")));
        if (fresh && std::filesystem::exists(out) && std::filesystem::equivalent(dir, out))
            throw InputError(fmt::format("--fresh would delete {}, one of the folders to merge", dir.string()));
        batch = settings;
    }
    prepareFolder(out, *batch, fresh);

    std::map<std::string, std::string> seen;  // job -> folder it came from
    for (const std::filesystem::path dir : dirs) {
        size_t count = 0;
        for (const json& job : readBatchJobs(dir, *batch)) {
            const std::string name = job.at("job").get<std::string>();
            if (const auto it = seen.find(name); it != seen.end())
                fmt::print(stderr, "warning: job {} is in {} and {}; keeping the one from {}\n", name, it->second,
                           dir.string(), dir.string());
            seen[name] = dir.string();
            copyInto(dir / "jobs" / (name + ".json"), out / "jobs" / (name + ".json"));
            const json runs = job.value("runs", json::object());  // none for a failed job; kept alive for the loop
            for (const auto& [runName, run] : runs.items()) {
                const json images = run.value("images", json::object());  // kept alive for the loop
                for (const auto& [kind, file] : images.items())
                    if (std::filesystem::exists(dir / file.get<std::string>()))
                        copyInto(dir / file.get<std::string>(), out / file.get<std::string>());
            }
            ++count;
        }
        fmt::print(stderr, "merged {} jobs from {}\n", count, dir.string());
    }
}

// Every env file is read and every scene file looked for up front, so that a typo in the last
// one fails now, not in an hour (or on the cluster).
BatchPlan planBatch(Options& options) {
    BatchPlan plan;
    plan.accels = parseBatchAccelerators(options.accels, options.env);
    plan.scenes = expandSceneList(options.scenes, options.env);
    for (const SceneArgument& scene : plan.scenes) {
        plan.sceneEnvs.push_back(scene.load(options.env));
        // Throws, naming the key to set, when the file is not there.
        const std::filesystem::path file = sceneFileOf(plan.sceneEnvs.back());
        const Env& env = plan.sceneEnvs.back();
        plan.animated.push_back(!file.empty() && isAnimatedScene(file) && env.get(keys::Batch::animate));
        if (plan.animated.back() && env.isExplicit(std::string(keys::Scene::frame.name())))
            warnOfRun(
                fmt::format("Scene::frame {} (from {}) ignored for {}: batch animates it over Animate::frames "
                            "({}); Batch::animate=false renders that one frame",
                            env.get(keys::Scene::frame), env.origin(keys::Scene::frame.name()), scene.id,
                            env.get(keys::Animate::frames)));
    }
    std::vector<std::pair<std::string, Env>> idsAndEnvs;
    for (size_t s = 0; s < plan.scenes.size(); ++s) idsAndEnvs.emplace_back(plan.scenes[s].id, plan.sceneEnvs[s]);
    std::vector<std::string> labels;
    for (const AccelConfig& config : plan.accels) labels.push_back(config.label);
    plan.settings = makeBatchSettings(idsAndEnvs, labels);
    return plan;
}

// The jobs of the batch in table order (scene, then accelerator) that this shard runs: every n-th.
std::vector<size_t> shardJobs(const BatchPlan& plan, const Shard& shard) {
    std::vector<size_t> mine;
    for (size_t j = 0; j < plan.scenes.size() * plan.accels.size(); ++j)
        if (j % size_t(shard.count) == size_t(shard.index)) mine.push_back(j);
    return mine;
}

// Job `job` of this shard, "J N/T" (its index J in table order; the N-th of the T jobs this run
// runs, as its progress names it), in the process of its own that runs it: its scene loaded
// (through the scene cache), then runJob.
json runJobHere(const Options& options, const BatchPlan& plan, const Shard& shard, const std::string& job) {
    const std::vector<size_t> mine = shardJobs(plan, shard);
    const size_t space = job.find(' ');
    size_t j = 0;
    if (space == std::string::npos || !parseNumber(std::string_view(job).substr(0, space), j) ||
        std::find(mine.begin(), mine.end(), j) == mine.end())
        throw InputError(fmt::format("{} {}: not a job of this shard", kChildJobOption, job));
    const BatchJob batchJob{plan, j, shard};
    const std::string jobLabel = fmt::format("[job {}]", job.substr(space + 1));
    Progress progress;
    if (batchJob.animated()) return finishedJobJson(runAnimationJob(options, batchJob, progress, jobLabel));
    progress.phase(fmt::format("{} {}: loading the scene", jobLabel, batchJob.scene().id));
    SceneLoadInfo info;
    const Scene scene = loadSceneFor(batchJob.sceneEnv(), true, &info);
    return finishedJobJson(runJob(options, batchJob, scene, info, progress, jobLabel));
}

// Runs this shard's jobs of the batch into `out`, each in a process of its own.
void runJobs(const Options& options, const BatchPlan& plan, const Shard& shard, const std::filesystem::path& out) {
    const std::vector<SceneArgument>& scenes = plan.scenes;
    const std::vector<Env>& sceneEnvs = plan.sceneEnvs;
    const std::vector<AccelConfig>& accels = plan.accels;
    prepareFolder(out, plan.settings, options.fresh);

    const size_t totalJobs = scenes.size() * accels.size();
    const std::vector<size_t> mine = shardJobs(plan, shard);
    fmt::print(
        stderr, "batch: {} scenes x {} accelerators = {} jobs{}; render threads ({}): {}; into {}\n", scenes.size(),
        accels.size(), totalJobs,
        shard.count > 1 ? fmt::format(", shard {}/{} runs {} of them", shard.index, shard.count, mine.size()) : "",
        options.env.threads >= 0 ? "--threads" : "Batch::threads",
        sceneEnvs.empty() ? 1 : renderThreads(options, sceneEnvs.front()), out.string());

    // Each job's result key first: a rerun keeps the finished jobs of this key (batch_resume.h).
    ResumeCount resume;
    std::vector<std::vector<size_t>> toRun(scenes.size());
    std::vector<std::vector<json>> kept(scenes.size());
    for (size_t j : mine) {
        const size_t s = j / accels.size(), a = j % accels.size();
        const std::string name = batchJobName(scenes[s].id, accels[a].label);
        const Env env = jobEnv(options, sceneEnvs[s], accels[a]);
        const StoredResult stored =
            options.fresh ? StoredResult{false, "of --fresh"}
                          : checkFinishedJob(out, name, jobResultKey(accels[a], env, plan.animated[s]), env);
        resume.add(stored);
        if (stored.keep)
            kept[s].push_back(json::parse(std::ifstream(out / "jobs" / (name + ".json"))));
        else
            toRun[s].push_back(j);
    }
    fmt::print(stderr, "batch: {}\n", resume.summary("jobs", "run"));

    const auto start = Progress::Clock::now();
    size_t jobNumber = 0, scenesFromCache = 0, scenesParsed = 0, failed = 0;
    for (size_t s = 0; s < scenes.size(); ++s) {
        std::vector<FinishedJob> finished;
        for (size_t j : toRun[s]) {
            const size_t a = j % accels.size();
            ++jobNumber;
            const JobOutcome outcome =
                runJobInChild(fmt::format("{} {}/{}", j, jobNumber, resume.toMeasure()), options.jobTimeout);
            if (outcome.passed()) {
                finished.push_back(finishedJobFromJson(outcome.result));
                (finished.back().job.value("scene_from_cache", false) ? scenesFromCache : scenesParsed) += 1;
                continue;
            }
            ++failed;
            fmt::print(stderr, "[job {}/{}] {} {}: failed: {}\n", jobNumber, resume.toMeasure(), scenes[s].id,
                       accels[a].label, outcome.failure());
            const BatchJob batchJob{plan, j, shard};
            writeFileAtomically(
                out / "jobs" / (batchJob.name() + ".json"),
                failedJobRecord(batchJob,
                                jobResultKey(accels[a], jobEnv(options, sceneEnvs[s], accels[a]), plan.animated[s]),
                                outcome)
                        .dump(2) +
                    "\n");
        }
        if (sceneEnvs[s].get(keys::Output::heatmap) && !plan.animated[s] && !finished.empty())
            writeSceneHeatmaps(out, scenes[s].id, finished, sceneEnvs[s].get(keys::Output::heatmapScale),
                               keptHeatmapScale(kept[s]));
    }
    fmt::print(stderr,
               "batch: {} jobs in {}{}; scene loads{}: {} read from the cache, {} parsed{}; {} builds, each "
               "serving both renders\n",
               jobNumber,
               Progress::formatDuration(std::chrono::duration<double>(Progress::Clock::now() - start).count()),
               failed ? fmt::format(", {} of them failed", failed) : "", failed ? " of the jobs that ran" : "",
               scenesFromCache, scenesParsed,
               scenesParsed && !sceneEnvs.empty() && !sceneEnvs.front().get(keys::Scene::cacheDir).empty()
                   ? fmt::format(" (and stored in {})", sceneEnvs.front().get(keys::Scene::cacheDir).string())
                   : "",
               jobNumber - failed);
}

// The arguments that make a shard's batch this one: the same scenes, accelerators and env layers
// (relative paths stay valid: the shards run in this working folder).
std::vector<std::string> shardArguments(const Options& options) {
    std::vector<std::string> arguments;
    for (const std::string& scenes : options.scenes) arguments.insert(arguments.end(), {"--scenes", scenes});
    arguments.insert(arguments.end(), {"--accel", options.accels});
    for (const std::string& plugin : options.env.plugins)
        arguments.insert(arguments.end(), {"--plugin", std::filesystem::absolute(plugin).string()});
    for (const std::string& file : options.env.envFiles) arguments.insert(arguments.end(), {"--env", file});
    for (const std::string& assignment : options.env.overrides) arguments.push_back("-D" + assignment);
    if (options.env.noGlobalEnv) arguments.push_back("--no-global-env");
    if (options.env.threads >= 0) arguments.insert(arguments.end(), {"--threads", std::to_string(options.env.threads)});
    return arguments;
}

// --slurm N: nothing runs here. The folders are made the batch's first (refused when they hold
// another batch, cleared with --fresh), so that no shard finds another batch in its folder hours
// later; then the shards and their merge are submitted.
void submitToSlurm(const Options& options, const BatchPlan& plan, const std::filesystem::path& out) {
    if (size_t(options.slurm) > plan.settings.jobCount())
        throw InputError(fmt::format("--slurm {}: the batch has {} jobs, so at most {} shards", options.slurm,
                                     plan.settings.jobCount(), plan.settings.jobCount()));
    const std::filesystem::path sbatch = findSbatch();
    SlurmBatch batch;
    batch.out = std::filesystem::absolute(out).lexically_normal();
    if (!batch.out.has_filename()) batch.out = batch.out.parent_path();  // "out/batch/"
    batch.shards = options.slurm;
    batch.program = std::filesystem::read_symlink("/proc/self/exe");
    batch.workingDir = std::filesystem::current_path();
    batch.batchArguments = shardArguments(options);
    // Enough CPUs for the scene with the most render threads; 0 (all the node has) for any.
    batch.cpusPerShard = 1;
    for (const Env& env : plan.sceneEnvs) {
        const int threads = renderThreads(options, env);
        batch.cpusPerShard = threads == 0 || batch.cpusPerShard == 0 ? 0 : std::max(batch.cpusPerShard, threads);
    }
    batch.sbatchArguments = options.slurmArgs;
    prepareFolder(batch.out, plan.settings, options.fresh);
    for (int shard = 0; shard < batch.shards; ++shard)
        prepareFolder(slurmShardFolder(batch.out, shard), plan.settings, options.fresh);
    fmt::print("{}", slurmSubmissionSummary(batch, submitSlurmBatch(batch, sbatch)));
}

// Returns the number of failed jobs in the tables.
size_t runBatch(Options& options) {
    if (options.child.isChild()) {
        const BatchPlan plan = planBatch(options);
        const Shard shard = options.shardGiven ? parseShard(options.shard) : Shard{};
        options.child.run([&] { return runJobHere(options, plan, shard, options.child.job); });
        return 0;
    }
    const std::filesystem::path out = prepareOutputFolder(options.out);
    if (!options.merge.empty()) {
        if (options.shardGiven) throw InputError("--merge and --shard do not go together");
        if (options.slurm)
            throw InputError("--merge and --slurm do not go together (--slurm N merges its shards itself)");
        mergeShards(options.merge, out, options.fresh);
    } else {
        if (options.slurm && options.shardGiven)
            throw InputError("--slurm and --shard do not go together (--slurm N makes the shards itself)");
        const Shard shard = options.shardGiven ? parseShard(options.shard) : Shard{};
        const BatchPlan plan = planBatch(options);
        if (options.slurm) {
            submitToSlurm(options, plan, out);
            return 0;
        }
        runJobs(options, plan, shard, out);
    }

    const BatchTables tables = writeBatchResults(out);
    for (const std::string& warning : tables.warnings) fmt::print(stderr, "warning: {}\n", warning);
    fmt::print("{}", tables.markdown);
    fmt::print(stderr, "wrote {0}/results.{{md,csv,json}}, {0}/contact_sheet.png, {0}/images, {0}/jobs\n",
               out.string());
    if (tables.failedJobs) fmt::print(stderr, "batch: {} failed jobs in the tables\n", tables.failedJobs);
    return tables.failedJobs;
}

}  // namespace

void addBatchCommand(CLI::App& app) {
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand(
        "batch",
        "render every scene with every chosen accelerator, without and with shadows: tables, images, contact sheet");
    addEnvOptions(*command, options->env);
    addThreadsOption(*command, options->env);
    addScenesOption(*command, options->scenes, "", "env/scenes.list");
    command->add_option("--accel", options->accels, "comma-separated accelerators")
        ->capture_default_str()
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    command
        ->add_option("--out", options->out, "output folder: results.{md,csv,json}, contact_sheet.png, images/, jobs/")
        ->capture_default_str()
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    CLI::Option* shard = command->add_option(
        "--shard", options->shard, "i/n: run every n-th job starting at job i (0-based, as $SLURM_ARRAY_TASK_ID)");
    command->add_option("--merge", options->merge,
                        "join the jobs of these batch output folders into --out and make its tables");
    command->add_flag("--fresh", options->fresh,
                      "first delete the batch --out holds (jobs/, images/, tables): needed when its settings differ; "
                      "without it a rerun keeps the jobs finished with the same result key");
    CLI::Option* slurm =
        command
            ->add_option("--slurm", options->slurm,
                         "N: run nothing here; submit the batch to Slurm (sbatch) as an array of N shards and a "
                         "merge job after them, into --out (scripts and logs in --out/slurm)")
            ->check(CLI::Range(1, 100000));
    command
        ->add_option("--slurm-args", options->slurmArgs,
                     "sbatch options for the shards and the merge, e.g. \"--partition=short --time=01:00:00 "
                     "--account=lab\"")
        ->needs(slurm);
    addJobTimeoutOption(*command, options->jobTimeout);
    addChildJobOptions(*command, options->child);
    command->callback([options, shard] {
        options->shardGiven = shard->count() > 0;
        runJobsGuarded([&] { return runBatch(*options); });
    });
}

}  // namespace bvhlab
