// `bvhlab animate`: an animated scene (BART's AFF) frame by frame under several structures and
// policies (update_policy.h), Embree's beside ours. Per frame each contender is brought to the
// frame's time (T_update) and traces the frame's primary and shadow rays (T_R, medians of
// rounds interleaved over the contenders, so that their ratios hold on a noisy machine); its
// statistics (SAH, EPO, bytes) and counters (N_IT, N_TR per ray) are read untimed. Writes
// DIR/animate.json (after every frame: an interrupted run keeps what it measured), the summary
// table DIR/animate.md, DIR/frames.csv, and with --images the frames as PNG. docs/animation.md.
#include "accel/registry.h"
#include "accel/verify/oracle.h"
#include "apps/animate/animate_report.h"
#include "apps/animate/update_policy.h"
#include "apps/cli/command_line.h"
#include "apps/cli/commands.h"
#include "apps/runtime/accel_config.h"
#include "apps/runtime/app_keys.h"
#include "apps/runtime/atomic_write.h"
#include "apps/runtime/comma_list.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/progress.h"
#include "apps/runtime/ray_sets.h"
#include "apps/runtime/run_record.h"
#include "apps/runtime/scene_choice.h"
#include "apps/runtime/scene_loading.h"
#include "apps/runtime/timing.h"
#include "apps/runtime/trace_rays.h"
#include "framework/config/common_keys.h"
#include "framework/core/error.h"
#include "framework/core/parse_number.h"
#include "framework/io/image_io.h"
#include "framework/render/renderer.h"
#include "framework/report/provenance.h"
#include "framework/scene/scene_loader.h"

#include <fmt/core.h>
#include <tbb/info.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>

namespace bvhlab {
namespace {

constexpr const char* kAllPolicies = "rebuild,refit,adaptive,twolevel";

struct AnimateOptions {
    EnvOptions env;
    std::string scene;
    std::string accels = "sahbvh,sahbvh8,ploc8,embree:Embree::quality=low,embree:Embree::quality=refit";
    std::string policies;  // empty: see AnimateRun
    std::string frames = "all";
    int rounds = 3;
    bool check = false;
    bool images = false;
    std::string out = "animate";
};

// --frames: all, or FIRST:END[:STRIDE] (END excluded, as Python's slices), within [0, count).
std::vector<int> parseFrames(const std::string& text, int count) {
    if (text == "all") {
        std::vector<int> all(size_t(count), 0);
        for (int i = 0; i < count; ++i) all[size_t(i)] = i;
        return all;
    }
    std::vector<std::string> parts(1);
    for (char ch : text) {
        if (ch == ':')
            parts.emplace_back();
        else
            parts.back().push_back(ch);
    }
    int first = 0, end = 0, stride = 1;
    if (parts.size() < 2 || parts.size() > 3 || !parseNumber(parts[0], first) || !parseNumber(parts[1], end) ||
        (parts.size() == 3 && (!parseNumber(parts[2], stride) || stride < 1)))
        throw InputError(fmt::format("--frames {}: not all, FIRST:END or FIRST:END:STRIDE", text));
    if (first < 0 || end > count || first >= end)
        throw InputError(fmt::format("--frames {}: the scene has frames 0 to {}", text, count - 1));
    std::vector<int> frames;
    for (int f = first; f < end; f += stride) frames.push_back(f);
    return frames;
}

struct AnimateContender {
    AccelConfig config;
    std::string policy;
    std::string label;
    Env env;
    std::unique_ptr<AnimatedStructure> structure;
    nlohmann::json result;  // as docs/animation.md describes a contender
    std::vector<double> primaryMs, shadowMs;
};

nlohmann::json optionalNumber(const std::optional<double>& value) {
    return value ? nlohmann::json(*value) : nlohmann::json();
}

nlohmann::json updateRow(int frame, float time, const FrameUpdate& update) {
    const BuildStats& s = update.stats;
    return {{"frame", frame},
            {"time", time},
            {"action", toString(update.action)},
            {"update_ms", s.buildMs},
            {"update_cpu_ms", s.buildCpuMs},
            {"sah", s.sah ? nlohmann::json(s.sah->cost) : nlohmann::json()},
            {"epo", optionalNumber(s.epo)},
            {"bytes", s.bytes ? nlohmann::json(*s.bytes) : nlohmann::json()}};
}

// The rays' counters per ray, or null where the structure does not count.
nlohmann::json traceColumns(size_t rays, double ms, const QueryCounters& counters) {
    const bool counted = counters.counting && rays > 0;
    return {{"rays", rays},
            {"ms", ms},
            {"n_it", counted ? nlohmann::json(double(counters.intersectionTests) / double(rays)) : nlohmann::json()},
            {"n_tr", counted ? nlohmann::json(double(counters.traversalSteps) / double(rays)) : nlohmann::json()}};
}

// --check's decider where a contender and the reference (Embree) differ: the double-precision
// brute force over the triangles (verify::Oracle); in a scene with spheres or cones, where an
// answer or the truth may be a quadric, our brute force over everything (naive, the quadrics'
// tests in double) decides.
class FrameJudge {
public:
    explicit FrameJudge(const PrimitiveSet& prims, const Env& env)
        : oracle_(PrimitiveSet{prims.triangles, prims.validTriangles()}) {
        if (!prims.hasQuadrics()) return;
        naive_ = createAccelerator("naive", env);
        naive_->build(prims);
    }

    bool wrongNearest(const Ray& ray, const Hit& answer) const {
        if (!naive_) return oracle_.judge(ray, answer).verdict == verify::Verdict::Wrong;
        QueryCounters counters;
        Hit truth;
        naive_->findNearest(ray, truth, counters);
        return !hitsAgree(answer, truth);
    }
    // An any-hit answer is judged as the structure's closest hit along the ray would be: a
    // shadow ray that grazes an edge is then a tie, as a primary ray's would be.
    bool wrongOccluded(const Accelerator& accel, const Ray& ray, bool answer) const {
        QueryCounters counters;
        if (naive_) return answer != naive_->isOccluded(ray, counters);
        Hit hit;
        if (answer && !accel.findNearest(ray, hit, counters)) return true;
        return oracle_.judge(ray, hit).verdict == verify::Verdict::Wrong;
    }

private:
    verify::Oracle oracle_;
    std::unique_ptr<Accelerator> naive_;
};

// --check: the contender's answers against the reference's; where they differ, the judge
// decides whether the contender is wrong or the two tie.
nlohmann::json checkAnswers(const Accelerator& accel, const Accelerator& reference, const FrameJudge& judge,
                            const RaySets& rays, int threads) {
    size_t wrong = 0, ties = 0;
    std::vector<Hit> hits(rays.primary.size()), expected(rays.primary.size());
    traceRays(accel, rays.primary, false, RayCoherence::Coherent, threads, false,
              {.hits = hits, .occluded = {}, .costs = {}});
    traceRays(reference, rays.primary, false, RayCoherence::Coherent, threads, false,
              {.hits = expected, .occluded = {}, .costs = {}});
    for (size_t i = 0; i < hits.size(); ++i)
        if (!hitsAgree(hits[i], expected[i])) (judge.wrongNearest(rays.primary[i], hits[i]) ? wrong : ties) += 1;
    std::vector<uint8_t> occluded(rays.shadow.size()), expectedOccluded(rays.shadow.size());
    traceRays(accel, rays.shadow, true, RayCoherence::Coherent, threads, false,
              {.hits = {}, .occluded = occluded, .costs = {}});
    traceRays(reference, rays.shadow, true, RayCoherence::Coherent, threads, false,
              {.hits = {}, .occluded = expectedOccluded, .costs = {}});
    for (size_t i = 0; i < occluded.size(); ++i)
        if (occluded[i] != expectedOccluded[i])
            (judge.wrongOccluded(accel, rays.shadow[i], occluded[i]) ? wrong : ties) += 1;
    return {{"checked", hits.size() + occluded.size()}, {"wrong", wrong}, {"ties", ties}};
}

class AnimateRun {
public:
    explicit AnimateRun(AnimateOptions& options) : options_(options) {
        const SceneChoice choice = chooseScene(options.scene, "", options.env);
        configs_ = parseAccelConfigList(options.accels);
        nameAccelerators(configs_, options.env);
        base_ = choice.load(options.env);
        checkAccelConfigs(configs_, base_);
        file_ = sceneFileOf(base_);
        if (!isAffFile(file_))
            throw InputError(
                fmt::format("{}: not an animated scene (bvhlab animate reads BART's .aff)", file_.string()));
        threads_ = base_.get(keys::SetRayTracing::threads);
        if (threads_ == 0) threads_ = tbb::info::default_concurrency();
        // --policies, else Animate::policy where an env file or -D set it, else all four.
        std::string policies = options.policies;
        if (policies.empty())
            policies = base_.isExplicit(std::string(keys::Animate::policy.name())) ? base_.get(keys::Animate::policy)
                                                                                   : kAllPolicies;
        for (const std::string& policy : splitCommaList(policies)) policies_.push_back(policy);
        for (const std::string& policy : policies_) parseUpdatePolicy(policy);  // refused before any work
        out_ = prepareOutputFolder(options.out);
    }

    size_t run() {
        Progress progress;
        progress.phase(fmt::format("reading {}", file_.string()));
        animated_ = loadAnimatedScene(file_);
        progress.finish();
        frames_ = parseFrames(options_.frames, animated_.frameCount);
        animated_.setTime(animated_.frameTime(frames_[0]));
        results_ = header();
        startContenders();
        for (size_t f = 0; f < frames_.size(); ++f) {
            progress.phase(
                fmt::format("{}: frame {} ({} of {})", animated_.scene.name, frames_[f], f + 1, frames_.size()));
            const bool validChanged = f > 0 && animated_.setTime(animated_.frameTime(frames_[f]));
            measureFrame(f, validChanged);
            progress.finish();
            writeFileAtomically(out_ / "animate.json", results().dump(2) + "\n");
        }
        const nlohmann::json all = results();
        writeFileAtomically(out_ / "animate.md", animateSummaryTable(all));
        writeFileAtomically(out_ / "frames.csv", animateFramesCsv(all));
        fmt::print("{}", animateSummaryTable(all));
        fmt::print(stderr, "wrote {}, animate.md and frames.csv there\n", (out_ / "animate.json").string());
        size_t failed = 0;
        for (const AnimateContender& c : contenders_) failed += c.result.contains("failed");
        return failed;
    }

private:
    static bool isAffFile(const std::filesystem::path& file) {
        std::string name = file.filename().string();
        if (name.ends_with(".gz")) name.resize(name.size() - 3);
        return name.ends_with(".aff");
    }

    nlohmann::json header() const {
        const Scene& scene = animated_.scene;
        return {{"provenance", provenanceJson()},
                {"scene",
                 {{"id", file_.stem().string()},
                  {"name", scene.name},
                  {"file", file_.string()},
                  {"frame_count", animated_.frameCount},
                  {"start_time", animated_.startTime},
                  {"end_time", animated_.endTime},
                  {"triangles", scene.triangleCount()},
                  {"moving_primitives", animated_.movingPrimitives().size()},
                  {"instances", SceneInstances(animated_).instances().size()}}},
                {"frames", frames_},
                {"threads", threads_},
                {"rounds", options_.rounds}};
    }

    nlohmann::json results() const {
        nlohmann::json all = results_;
        all["run"] = runJson();
        all["contenders"] = nlohmann::json::array();
        for (const AnimateContender& c : contenders_) all["contenders"].push_back(c.result);
        return all;
    }

    // The adaptive policy reads its structure's statistics in its update time, to decide by
    // their SAH: our BVHs' EPO, which it does not decide by, is left out of them.
    static void withoutEpo(Env& env, const std::string& accel) {
        const char* const kEpoKey = "BVH::epoMaxTriangles";
        const std::vector<std::string> readers = acceleratorsReading(kEpoKey);
        if (std::find(readers.begin(), readers.end(), accel) != readers.end())
            env.set(kEpoKey, "0", "bvhlab animate: adaptive decides by the SAH alone");
    }

    // The policies `config` runs under: its own Animate::policy (NAME:Animate::policy=refit),
    // else each of --policies.
    std::vector<std::string> policiesOf(const AccelConfig& config) const {
        const std::string own = std::string(keys::Animate::policy.name()) + "=";
        for (const std::string& assignment : config.overrides)
            if (assignment.starts_with(own)) return {assignment.substr(own.size())};
        return policies_;
    }

    // Each structure under each of its policies, built at the first frame.
    void startContenders() {
        for (const AccelConfig& config : configs_)
            for (const std::string& policy : policiesOf(config)) {
                AnimateContender c{config, policy, config.label + "/" + policy, accelConfigEnv(config, base_), {}, {},
                                   {},     {}};
                c.env.set(keys::Animate::policy, policy, "bvhlab animate --policies");
                if (policy == "adaptive") withoutEpo(c.env, config.name);
                c.env.set(keys::SetRayTracing::threads, std::to_string(threads_), "bvhlab animate --threads");
                c.result = {{"label", c.label},
                            {"accel", config.label},
                            {"policy", policy},
                            {"policy_keys",
                             {{keys::Animate::sahGrowth.name(), c.env.get(keys::Animate::sahGrowth)},
                              {keys::Animate::rebuildEvery.name(), c.env.get(keys::Animate::rebuildEvery)}}},
                            {"embree", config.name == "embree"},
                            {"rows", nlohmann::json::array()}};
                contenders_.push_back(std::move(c));
            }
        for (AnimateContender& c : contenders_)
            guard(c, [&] {
                c.structure = std::make_unique<AnimatedStructure>(animated_, c.config.name, c.env);
                c.result["rows"].push_back(updateRow(frames_[0], animated_.time(), c.structure->start()));
            });
    }

    // A contender that throws is failed with the reason and left out of the frames after; one
    // that cannot run its policy is skipped.
    template <typename Body>
    void guard(AnimateContender& c, Body&& body) {
        if (!c.structure && c.result["rows"].size() > 0) return;
        try {
            body();
        } catch (const NoUpdateError& e) {
            c.result["skipped"] = e.what();
            c.structure.reset();
            fmt::print(stderr, "{}: skipped: {}\n", c.label, e.what());
        } catch (const std::exception& e) {
            c.result["failed"] = e.what();
            c.structure.reset();
            fmt::print(stderr, "{}: failed: {}\n", c.label, e.what());
        }
    }

    std::vector<AnimateContender*> running() {
        std::vector<AnimateContender*> out;
        for (AnimateContender& c : contenders_)
            if (c.structure) out.push_back(&c);
        return out;
    }

    void measureFrame(size_t f, bool validChanged) {
        const int frame = frames_[f];
        const float time = animated_.time();
        std::vector<AnimateContender*> active = running();
        // The order turns every frame, so that no contender always runs first on a cold cache.
        if (!active.empty())
            std::rotate(active.begin(), active.begin() + std::ptrdiff_t(f % active.size()), active.end());
        if (f > 0)
            for (AnimateContender* c : active)
                guard(*c, [&] {
                    c->result["rows"].push_back(updateRow(frame, time, c->structure->advance(validChanged)));
                });

        // The frame's rays, from Embree's hits (untimed): every contender traces the same ones.
        const std::unique_ptr<Accelerator> reference = createAccelerator("embree", base_);
        reference->build(animated_.scene.primitives());
        const RaySets rays = sceneRaySets(animated_.scene, base_, *reference);
        active = running();
        for (AnimateContender* c : active) c->primaryMs.clear(), c->shadowMs.clear();
        std::vector<QueryCounters> primaryCounts(active.size()), shadowCounts(active.size());
        for (int round = 0; round < options_.rounds; ++round)
            for (size_t k = 0; k < active.size(); ++k) {
                AnimateContender& c = *active[(k + size_t(round)) % active.size()];
                const size_t slot = (k + size_t(round)) % active.size();
                guard(c, [&] {
                    const Accelerator& accel = c.structure->accelerator();
                    const PassResult primary = tracePasses(accel, rays.primary, false, RayCoherence::Coherent, threads_,
                                                           1, QueryKind::Batch, round == 0);
                    const PassResult shadow = tracePasses(accel, rays.shadow, true, RayCoherence::Coherent, threads_, 1,
                                                          QueryKind::Batch, round == 0);
                    c.primaryMs.push_back(primary.usPerQuery * double(rays.primary.size()) * 1e-3);
                    c.shadowMs.push_back(shadow.usPerQuery * double(rays.shadow.size()) * 1e-3);
                    if (round == 0) primaryCounts[slot] = primary.counters, shadowCounts[slot] = shadow.counters;
                });
            }
        std::optional<FrameJudge> judge;
        if (options_.check) judge.emplace(animated_.scene.primitives(), base_);
        for (size_t k = 0; k < active.size(); ++k) {
            AnimateContender& c = *active[k];
            if (!c.structure) continue;
            nlohmann::json& row = c.result["rows"].back();
            row["primary"] = traceColumns(rays.primary.size(), median(c.primaryMs), primaryCounts[k]);
            row["shadow"] = traceColumns(rays.shadow.size(), median(c.shadowMs), shadowCounts[k]);
            if (judge)
                guard(c, [&] {
                    row["agreement"] = checkAnswers(c.structure->accelerator(), *reference, *judge, rays, threads_);
                });
        }
        if (options_.images) writeImage(frame, *reference);
    }

    // The frame as `bvhlab render` would draw it, through the reference structure.
    void writeImage(int frame, const Accelerator& accel) const {
        const Camera camera(resolveCamera(animated_.scene, base_));
        const RenderSettings settings = RenderSettings::fromEnv(base_, animated_.scene, camera.spec());
        Framebuffer fb(camera.spec().width, camera.spec().height);
        render(animated_.scene, accel, camera, settings, fb);
        writePng(out_ / fmt::format("frame_{:04}.png", frame), fb);
    }

    AnimateOptions& options_;
    std::vector<AccelConfig> configs_;
    std::vector<std::string> policies_;
    Env base_{programKeys()};
    std::filesystem::path file_, out_;
    int threads_ = 1;
    AnimatedScene animated_;
    std::vector<int> frames_;
    nlohmann::json results_;
    std::vector<AnimateContender> contenders_;
};

}  // namespace

void addAnimateCommand(CLI::App& app) {
    auto options = std::make_shared<AnimateOptions>();
    CLI::App* command = app.add_subcommand(
        "animate", "an animated scene (.aff) frame by frame: update and trace time per policy, against Embree's");
    addEnvOptions(*command, options->env);
    addThreadsOption(*command, options->env);
    command->add_option("--scene", options->scene, "animated scene file (.aff), or NAME for env/scenes/NAME.env")
        ->required();
    command->add_option("--accel", options->accels, "structures, NAME or NAME:Key=value, comma-separated")
        ->capture_default_str();
    command->add_option(
        "--policies", options->policies,
        "policies each structure runs under, comma-separated (rebuild, refit, adaptive, twolevel); default: "
        "Animate::policy where an env file or -D sets it, else all four; a structure given its own, "
        "NAME:Animate::policy=P, runs under that one");
    command->add_option("--frames", options->frames, "all, or FIRST:END[:STRIDE] (END excluded)")
        ->capture_default_str();
    command->add_option("--rounds", options->rounds, "traces of each frame's rays per contender (median)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    command->add_flag("--check", options->check,
                      "check every measured frame's answers against Embree's (a double-precision brute force "
                      "decides where they differ)");
    command->add_flag("--images", options->images, "write each measured frame as DIR/frame_NNNN.png");
    command->add_option("--out", options->out, "output folder: animate.json, animate.md, frames.csv")
        ->capture_default_str();
    command->callback([options] { runJobsGuarded([&] { return AnimateRun(*options).run(); }); });
}

}  // namespace bvhlab
