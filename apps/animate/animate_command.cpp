// `bvhlab animate`: an animated scene (BART's AFF) frame by frame under several structures and
// policies (update_policy.h), Embree's beside ours, measured by AnimationRun (animation_run.h).
// Writes DIR/animate.json (after every frame: an interrupted run keeps what it measured), the
// summary table DIR/animate.md, DIR/frames.csv, and with --images the frames as PNG.
// docs/animation.md.
#include "apps/animate/animate_report.h"
#include "apps/animate/animation_run.h"
#include "apps/cli/command_line.h"
#include "apps/cli/commands.h"
#include "apps/runtime/accel_config.h"
#include "apps/runtime/app_keys.h"
#include "apps/runtime/atomic_write.h"
#include "apps/runtime/comma_list.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/progress.h"
#include "apps/runtime/run_record.h"
#include "apps/runtime/scene_choice.h"
#include "apps/runtime/scene_loading.h"
#include "framework/config/common_keys.h"
#include "framework/core/error.h"
#include "framework/io/image_io.h"
#include "framework/render/renderer.h"
#include "framework/report/provenance.h"
#include "framework/scene/scene_loader.h"

#include <fmt/core.h>
#include <tbb/info.h>
#include <nlohmann/json.hpp>

#include <filesystem>

namespace bvhlab {
namespace {

constexpr const char* kAllPolicies = "rebuild,refit,adaptive,twolevel";

struct AnimateOptions {
    EnvOptions env;
    std::string scene;
    std::string accels = "sahbvh,sahbvh8,ploc8,embree:Embree::quality=low,embree:Embree::quality=refit";
    std::string policies;  // empty: see AnimateRun
    std::string frames;    // empty: Animate::frames
    int rounds = 3;
    bool check = false;
    bool images = false;
    std::string out = "animate";
};

class AnimateRun {
public:
    explicit AnimateRun(AnimateOptions& options) : options_(options) {
        const SceneChoice choice = chooseScene(options.scene, "", options.env);
        configs_ = parseAccelConfigList(options.accels);
        nameAccelerators(configs_, options.env);
        base_ = choice.load(options.env);
        checkAccelConfigs(configs_, base_);
        file_ = sceneFileOf(base_);
        if (!isAnimatedScene(file_))
            throw InputError(
                fmt::format("{}: not an animated scene (bvhlab animate reads BART's .aff)", file_.string()));
        if (base_.isExplicit(std::string(keys::Scene::frame.name())))
            warnOfRun(
                fmt::format("Scene::frame {} (from {}) ignored: bvhlab animate measures the frames of --frames "
                            "or Animate::frames",
                            base_.get(keys::Scene::frame), base_.origin(keys::Scene::frame.name())));
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
        AnimatedScene animated = loadAnimatedScene(file_);
        progress.finish();
        const std::string frames = options_.frames.empty() ? base_.get(keys::Animate::frames) : options_.frames;
        AnimationRun measure(
            animated, base_,
            {parseFrames(frames, animated.frameCount,
                         options_.frames.empty() ? std::string(keys::Animate::frames.name()) : std::string("--frames")),
             options_.rounds, options_.check, threads_});
        for (const AccelConfig& config : configs_)
            for (const std::string& policy : policiesOf(config)) measure.addContender(config, policy);
        nlohmann::json results = measure.header(file_);
        results["provenance"] = provenanceJson();
        measure.run([&](int frame, const Accelerator& reference) {
            results["run"] = runJson();
            results["contenders"] = measure.contenders();
            writeFileAtomically(out_ / "animate.json", results.dump(2) + "\n");
            if (options_.images) writeImage(animated.scene, frame, reference);
        });
        writeFileAtomically(out_ / "animate.md", animateSummaryTable(results));
        writeFileAtomically(out_ / "frames.csv", animateFramesCsv(results));
        fmt::print("{}", animateSummaryTable(results));
        fmt::print(stderr, "wrote {}, animate.md and frames.csv there\n", (out_ / "animate.json").string());
        return measure.failedCount();
    }

private:
    // The policies `config` runs under: its own Animate::policy (NAME:Animate::policy=refit),
    // else each of --policies.
    std::vector<std::string> policiesOf(const AccelConfig& config) const {
        const std::string own = std::string(keys::Animate::policy.name()) + "=";
        for (const std::string& assignment : config.overrides)
            if (assignment.starts_with(own)) return {assignment.substr(own.size())};
        return policies_;
    }

    // The frame as `bvhlab render` would draw it, through the reference structure.
    void writeImage(const Scene& scene, int frame, const Accelerator& accel) const {
        const Camera camera(resolveCamera(scene, base_));
        const RenderSettings settings = RenderSettings::fromEnv(base_, scene, camera.spec());
        Framebuffer fb(camera.spec().width, camera.spec().height);
        render(scene, accel, camera, settings, fb);
        writePng(out_ / fmt::format("frame_{:04}.png", frame), fb);
    }

    AnimateOptions& options_;
    std::vector<AccelConfig> configs_;
    std::vector<std::string> policies_;
    Env base_{programKeys()};
    std::filesystem::path file_, out_;
    int threads_ = 1;
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
    command->add_option("--frames", options->frames,
                        "all, or FIRST:END[:STRIDE] (END excluded); default: Animate::frames");
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
