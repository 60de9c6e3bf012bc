// `bvhlab spd SCENE.nff... --out DIR`: the SPD test (framework/render/spd_tracer.h) with each
// chosen accelerator, beside Havran's published figures (apps/spd/havran_reference.h):
// DIR/spd.json, DIR/spd.md and an image per scene and accelerator.
#include "apps/cli/commands.h"

#include "accel/registry.h"
#include "apps/cli/command_line.h"
#include "apps/runtime/accel_config.h"
#include "apps/runtime/app_keys.h"
#include "apps/runtime/atomic_write.h"
#include "apps/runtime/comma_list.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/progress.h"
#include "apps/runtime/scene_choice.h"
#include "apps/runtime/scene_loading.h"
#include "apps/spd/havran_reference.h"
#include "framework/config/common_keys.h"
#include "framework/core/timed_build.h"
#include "framework/io/image_io.h"
#include "framework/render/spd_tracer.h"
#include "framework/report/build_stats_json.h"
#include "framework/report/provenance.h"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

namespace bvhlab {
namespace {

double perRay(uint64_t count, uint64_t rays) { return rays ? double(count) / double(rays) : 0.0; }

nlohmann::json invariantsJson(const SpdCounts& c) {
    return {{"PrimaryRay", c.primaryRays},     {"UsedIntPrimRay", c.usedIntPrimRays}, {"ShadowRay", c.shadowRays},
            {"UsedIntShadRay", c.usedIntShadRays}, {"SecondaryRay", c.secondaryRays}, {"UsedIntSecRay", c.usedIntSecRays},
            {"AllRays", c.allRays()},          {"IntersRequired", c.intersRequired()}};
}

nlohmann::json accelJson(const std::string& label, const BuildStats& build, const SpdResult& r, bool counted) {
    const uint64_t rays = r.counts.allRays();
    QueryCounters all = r.closest;
    all += r.shadow;
    const auto counter = [&](uint64_t v) { return counted ? nlohmann::json(perRay(v, rays)) : nlohmann::json(); };
    return {{"accel", label},
            {"build_ms", build.buildMs},
            {"figures", figuresJson(build.figures)},  // the structure's own (a grid's N_V, N_EV, N_OIV)
            {"trace_ms", r.traceMs},
            {"threads", r.threads},
            {"invariants", invariantsJson(r.counts)},
            {"n_it", counter(all.intersectionTests)},
            {"n_ts", counter(all.traversalSteps)},
            {"n_it_triangle", counter(all.triangleTests())},
            {"n_it_sphere", counter(all.sphereTests)},
            {"n_it_cone", counter(all.coneTests)},
            {"skipped",
             {{"shadow_backfacing", r.counts.shadowRaysSkippedBackfacing},
              {"cut_by_depth", r.counts.raysCutByDepth},
              {"total_internal_reflections", r.counts.totalInternalReflections}}},
            {"reflection_rays", r.counts.reflectionRays},
            {"refraction_rays", r.counts.refractionRays}};
}

std::string percentDiff(double ours, double theirs) {
    if (theirs == 0.0) return ours == 0.0 ? "0.00 %" : "n/a";
    return fmt::format("{:+.2f} %", 100.0 * (ours - theirs) / theirs);
}

// spd.md: per scene, our invariants beside Havran's, then N_IT / N_TS per accelerator beside
// his best grid and octree.
std::string markdown(const nlohmann::json& results) {
    std::string md = "# The SPD test: bvhlab beside Havran's GOLEM statistics\n\n";
    md += "Rules: SPD_Readme.txt \"Testing Procedures\" (framework/render/spd_tracer.h). Havran's figures: "
          "havran_stats_grids.txt and havran_stats_octrees.txt (1999).\n\n";
    for (const nlohmann::json& scene : results["scenes"]) {
        md += fmt::format("## {}\n\n", scene["scene"].get<std::string>());
        const nlohmann::json& ours = scene["accels"][0]["invariants"];
        const nlohmann::json& havran = scene["havran"];
        md += "| invariant | bvhlab | Havran | difference |\n|---|---:|---:|---:|\n";
        for (const char* name : kHavranInvariants) {
            const bool known = havran.contains("invariants") && havran["invariants"].contains(name);
            const double theirs = known ? havran["invariants"][name].get<double>() : 0.0;
            md += fmt::format("| {} | {} | {} | {} |\n", name, ours[name].get<uint64_t>(),
                              known ? fmt::format("{:.0f}", theirs) : "n/a",
                              known ? percentDiff(ours[name].get<double>(), theirs) : "n/a");
        }
        md += "\n| structure | N_IT per ray | N_TS per ray | T_B ms | trace ms |\n|---|---:|---:|---:|---:|\n";
        for (const char* kind : {"best_grid", "best_octree"}) {
            if (!havran.contains(kind) || havran[kind].is_null()) continue;
            md += fmt::format("| Havran's {} | {:.2f} | {:.2f} | | |\n", kind == std::string("best_grid") ? "best grid" : "best octree",
                              havran[kind]["n_it"].get<double>(), havran[kind]["n_ts"].get<double>());
        }
        for (const nlohmann::json& a : scene["accels"]) {
            const auto cell = [](const nlohmann::json& v) { return v.is_null() ? std::string("n/a") : fmt::format("{:.2f}", v.get<double>()); };
            md += fmt::format("| {} | {} | {} | {:.1f} | {:.0f} |\n", a["accel"].get<std::string>(), cell(a["n_it"]),
                              cell(a["n_ts"]), a["build_ms"].get<double>(), a["trace_ms"].get<double>());
        }
        md += "\n";
    }
    return md;
}

}  // namespace

void addSpdCommand(CLI::App& app) {
    struct Options {
        EnvOptions env;
        std::vector<std::string> scenes;
        std::string accels;
        std::string out = "out/spd";
    };
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand(
        "spd", "trace SPD scenes by the SPD rules; Havran's ray invariants and N_IT, N_TS beside his (DIR/spd.md)");
    addEnvOptions(*command, options->env);
    addThreadsOption(*command, options->env);
    command->add_option("scenes", options->scenes, "NFF scene files (SPD scenes have their own viewpoint and lights)")
        ->required();
    command->add_option("--accel", options->accels,
                        "comma-separated NAME or NAME:Key=value:... (default: ASDS::type); the first one's invariants "
                        "are compared with Havran's");
    command->add_option("--out", options->out, "output folder: spd.json, spd.md, SCENE.ACCEL.png")->capture_default_str();
    command->callback([options] {
        const int code = runGuarded([&] {
            const std::filesystem::path out = prepareOutputFolder(options->out);
            std::vector<AccelConfig> configs = parseAccelConfigList(options->accels);
            nameAccelerators(configs, options->env);
            const Env base = chooseScene("", "", options->env).load(options->env);
            if (configs.empty()) configs = parseAccelConfigList(base.get(keys::ASDS::type));
            checkAccelConfigs(configs, base);
            const auto havran = readHavranReference(base.get(keys::Spd::reference));
            SpdRules rules;
            rules.maxDepth = base.get(keys::Spd::maxDepth);
            rules.threads = base.get(keys::SetRayTracing::threads);

            nlohmann::json results = {{"provenance", provenanceJson()},
                                      {"rules", {{"max_depth", rules.maxDepth}}},
                                      {"scenes", nlohmann::json::array()}};
            Progress progress;
            for (const std::string& file : options->scenes) {
                Env env = base;
                env.set(keys::Scene::file, std::filesystem::absolute(file).string(), "bvhlab spd");
                const Scene scene = loadSceneFor(env);
                const std::vector<std::string> twoSided = splitCommaList(base.get(keys::Spd::twoSidedScenes));
                rules.twoSided = std::find(twoSided.begin(), twoSided.end(), scene.name) != twoSided.end();
                nlohmann::json sceneJson = {
                    {"scene", scene.name}, {"two_sided", rules.twoSided}, {"accels", nlohmann::json::array()}};
                if (const auto it = havran.find(scene.name); it != havran.end()) {
                    const HavranScene& h = it->second;
                    sceneJson["havran"]["invariants"] = h.invariants;
                    for (const auto& [key, best] : {std::pair{"best_grid", h.bestGrid}, std::pair{"best_octree", h.bestOctree}})
                        sceneJson["havran"][key] = best ? nlohmann::json{{"n_it", best->nIt}, {"n_ts", best->nTs}} : nlohmann::json();
                } else {
                    sceneJson["havran"] = nlohmann::json::object();
                }
                for (const AccelConfig& config : configs) {
                    const Env accelEnv = accelConfigEnv(config, env);
                    progress.phase(fmt::format("{} {}: building", scene.name, config.label));
                    auto accel = createAccelerator(config.name, accelEnv);
                    const BuildStats build = timedBuild(*accel, scene.primitives());
                    const uint64_t rows = uint64_t(scene.camera ? scene.camera->height + 1 : 0);
                    progress.phase(fmt::format("{} {}: tracing", scene.name, config.label), rows);
                    Framebuffer fb(scene.camera ? scene.camera->width : 1, scene.camera ? scene.camera->height : 1);
                    const SpdResult result =
                        traceSpd(scene, *accel, rules, fb, [&](uint64_t rays) { progress.advance(1, rays); });
                    progress.finish();
                    writePng(out / fmt::format("{}.{}.png", scene.name, config.label), fb);
                    sceneJson["accels"].push_back(accelJson(config.label, build, result, accel->hasCounters()));
                }
                results["scenes"].push_back(sceneJson);
            }
            writeFileAtomically(out / "spd.json", results.dump(2) + "\n");
            const std::string md = markdown(results);
            writeFileAtomically(out / "spd.md", md);
            fmt::print("{}", md);
            fmt::print(stderr, "wrote {}/spd.{{json,md}} and the images\n", out.string());
        });
        if (code != 0) throw CLI::RuntimeError(code);
    });
}

}  // namespace bvhlab
