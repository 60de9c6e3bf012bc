// `bvhlab spd SCENE.nff... --out DIR`: the SPD test (framework/render/spd_tracer.h) with each
// chosen accelerator, beside Havran's published figures (apps/spd/havran_reference.h), an octree's
// beside the column of his octree tables it was built as: DIR/spd.json, DIR/spd.md and an image
// per scene and accelerator. Each scene x accelerator is a job in a process of its own
// (apps/runtime/child_job.h): one that crashes, throws or runs past --job-timeout is a failed row
// with its reason, and the others run.
#include "apps/cli/commands.h"

#include "accel/registry.h"
#include "apps/cli/command_line.h"
#include "apps/runtime/accel_config.h"
#include "apps/runtime/app_keys.h"
#include "apps/runtime/atomic_write.h"
#include "apps/runtime/build_watch.h"
#include "apps/runtime/child_job.h"
#include "apps/runtime/comma_list.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/progress.h"
#include "apps/runtime/run_record.h"
#include "apps/runtime/scene_choice.h"
#include "apps/runtime/scene_loading.h"
#include "apps/spd/havran_reference.h"
#include "framework/config/common_keys.h"
#include "framework/core/accelerator.h"
#include "framework/core/error.h"
#include "framework/core/parse_number.h"
#include "framework/core/timed_build.h"
#include "framework/io/image_io.h"
#include "framework/render/spd_tracer.h"
#include "framework/report/build_stats_json.h"
#include "framework/report/provenance.h"
#include "framework/report/query_counters_json.h"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <iterator>
#include <map>
#include <optional>
#include <utility>

namespace bvhlab {
namespace {

double perRay(uint64_t count, uint64_t rays) { return rays ? double(count) / double(rays) : 0.0; }

nlohmann::json invariantsJson(const SpdCounts& c) {
    return {{"PrimaryRay", c.primaryRays},     {"UsedIntPrimRay", c.usedIntPrimRays},
            {"ShadowRay", c.shadowRays},       {"UsedIntShadRay", c.usedIntShadRays},
            {"SecondaryRay", c.secondaryRays}, {"UsedIntSecRay", c.usedIntSecRays},
            {"AllRays", c.allRays()},          {"IntersRequired", c.intersRequired()}};
}

nlohmann::json accelJson(const std::string& label, const BuildStats& build, const SpdResult& r, bool counted,
                         nlohmann::json havran) {
    const uint64_t rays = r.counts.allRays();
    QueryCounters all = r.closest;
    all += r.shadow;
    nlohmann::json accel = {
        {"accel", label},
        {"build_ms", build.buildMs},
        {"figures", figuresJson(build.figures)},  // the structure's own (a grid's N_V, N_EV, N_OIV)
        {"trace_ms", r.traceMs},
        {"threads", r.threads},
        {"invariants", invariantsJson(r.counts)},
        {"n_it_triangle", counted ? nlohmann::json(perRay(all.triangleTests(), rays)) : nlohmann::json()},
        {"skipped",
         {{"shadow_backfacing", r.counts.shadowRaysSkippedBackfacing},
          {"cut_by_depth", r.counts.raysCutByDepth},
          {"total_internal_reflections", r.counts.totalInternalReflections}}},
        {"reflection_rays", r.counts.reflectionRays},
        {"refraction_rays", r.counts.refractionRays},
        {"havran", std::move(havran)}};  // the column of his tables this run stands beside, or null
    accel.update(queryCountersJson(all, double(rays), counted));
    return accel;
}

// The column of Havran's tables that a run of the octree plugin stands beside: the table of its
// traversal and subdivision ("Octree84-C"), the column of its maximum depth (his are 4 to 7).
std::optional<std::pair<std::string, size_t>> havranOctreeColumn(const AccelConfig& config, const Env& env) {
    if (config.name != "octree") return std::nullopt;
    const nlohmann::json keys = env.toJson();
    const auto value = [&](const char* key) {
        return keys.contains(key) ? keys[key]["value"].get<std::string>() : std::string();
    };
    const std::string traversal = value("Octree::traversal"), subdivision = value("Octree::subdivision");
    double depth = 0.0;
    if (traversal.rfind("octree", 0) != 0 || !parseNumber(value("Octree::maxDepth"), depth)) return std::nullopt;
    const int column = int(depth) - kHavranFirstDepth;
    if (column < 0 || column > 3) return std::nullopt;
    return std::pair{fmt::format("Octree{}-{}", traversal.substr(6), subdivision == "adaptive" ? "A" : "C"),
                     size_t(column)};
}

// Havran's figures of `column` in `table` of the scene, for the rows bvhlab measures.
nlohmann::json havranOctreeJson(const HavranScene& scene, const std::string& table, size_t column) {
    const auto t = scene.tables.find(table);
    if (t == scene.tables.end()) return nullptr;
    nlohmann::json values = nlohmann::json::object();
    for (const char* row : kHavranOctreeRows)
        if (const auto r = t->second.find(row); r != t->second.end() && column < r->second.size())
            values[row] = r->second[column];
    return {{"table", table}, {"max_depth", int(column) + kHavranFirstDepth}, {"values", values}};
}

std::string percentDiff(double ours, double theirs) {
    if (theirs == 0.0) return ours == 0.0 ? "0.00 %" : "n/a";
    return fmt::format("{:+.2f} %", 100.0 * (ours - theirs) / theirs);
}

// The octree runs beside the column of Havran's octree tables each stands beside (empty when no
// run has one): his row, then ours with the difference. His octree tables' N_IT is the tests per
// intersection required (IntersRequired), not per ray (docs/spd.md, "Havran's octrees"): ours is
// set beside it so computed, and given per ray in the last column.
std::string octreeMarkdown(const nlohmann::json& accels) {
    std::string md;
    for (const nlohmann::json& a : accels) {
        if (!a.contains("havran") || a["havran"].is_null()) continue;
        if (md.empty()) {
            md = "| octree | N_IN | N_V | N_EV | N_OIV | N_IT per IntersRequired | N_TS | N_ETS | N_EETS "
                 "| N_IT per ray |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        }
        const nlohmann::json& havran = a["havran"]["values"];
        const nlohmann::json& invariants = a["invariants"];
        const double required = invariants["IntersRequired"].get<double>(), rays = invariants["AllRays"].get<double>();
        std::string theirs = fmt::format("| Havran's {}, depth {} |", a["havran"]["table"].get<std::string>(),
                                         a["havran"]["max_depth"].get<int>());
        std::string ours = fmt::format("| {} |", a["accel"].get<std::string>());
        for (const char* row : kHavranOctreeRows) {
            const std::string name(row);
            nlohmann::json mine;
            if (name == "N_IT" && !a["n_it"].is_null() && required > 0.0)
                mine = a["n_it"].get<double>() * rays / required;
            else if (name == "N_TS")
                mine = a["n_tr"];
            else if (a["figures"].contains(name))
                mine = a["figures"][name]["value"];
            const bool whole = name == "N_IN" || name == "N_V" || name == "N_EV" || name == "N_OIV";
            const auto number = [&](double v) { return whole ? fmt::format("{:.0f}", v) : fmt::format("{:.2f}", v); };
            theirs += havran.contains(name) ? fmt::format(" {} |", number(havran[name].get<double>())) : " n/a |";
            if (mine.is_null())
                ours += " n/a |";
            else if (!havran.contains(name))
                ours += fmt::format(" {} |", number(mine.get<double>()));
            else
                ours += fmt::format(" {} ({}) |", number(mine.get<double>()),
                                    percentDiff(mine.get<double>(), havran[name].get<double>()));
        }
        theirs += " |";
        ours += a["n_it"].is_null() ? " n/a |" : fmt::format(" {:.2f} |", a["n_it"].get<double>());
        md += theirs + "\n" + ours + "\n";
    }
    return md.empty() ? md : md + "\n";
}

// spd.md: per scene, our invariants beside Havran's, then N_IT / N_TS per accelerator beside
// his best grid and octree, then the octree runs beside his octree tables.
std::string markdown(const nlohmann::json& results) {
    std::string md = "# The SPD test: bvhlab beside Havran's GOLEM statistics\n\n";
    md +=
        "Rules: SPD_Readme.txt \"Testing Procedures\" (framework/render/spd_tracer.h). Havran's figures: "
        "havran_stats_grids.txt and havran_stats_octrees.txt (1999).\n\n";
    for (const nlohmann::json& scene : results["scenes"]) {
        md += fmt::format("## {}\n\n", scene["scene"].get<std::string>());
        // The invariants of the first structure that ran (they are the scene's, whichever traced it).
        const auto ran = std::find_if(scene["accels"].begin(), scene["accels"].end(),
                                      [](const nlohmann::json& a) { return !a.contains("failed"); });
        const nlohmann::json ours = ran == scene["accels"].end() ? nlohmann::json() : (*ran)["invariants"];
        const nlohmann::json& havran = scene["havran"];
        md += "| invariant | bvhlab | Havran | difference |\n|---|---:|---:|---:|\n";
        for (const char* name : kHavranInvariants) {
            const bool known = havran.contains("invariants") && havran["invariants"].contains(name);
            const double theirs = known ? havran["invariants"][name].get<double>() : 0.0;
            md += fmt::format("| {} | {} | {} | {} |\n", name,
                              ours.is_null() ? "n/a" : fmt::format("{}", ours[name].get<uint64_t>()),
                              known ? fmt::format("{:.0f}", theirs) : "n/a",
                              known && !ours.is_null() ? percentDiff(ours[name].get<double>(), theirs) : "n/a");
        }
        md += "\n| structure | N_IT per ray | N_TS per ray | T_B ms | trace ms |\n|---|---:|---:|---:|---:|\n";
        for (const char* kind : {"best_grid", "best_octree"}) {
            if (!havran.contains(kind) || havran[kind].is_null()) continue;
            md += fmt::format("| Havran's {} | {:.2f} | {:.2f} | | |\n",
                              kind == std::string("best_grid") ? "best grid" : "best octree",
                              havran[kind]["n_it"].get<double>(), havran[kind]["n_ts"].get<double>());
        }
        for (const nlohmann::json& a : scene["accels"]) {
            if (a.contains("failed")) {
                md += fmt::format("| {} | failed: {} | | | |\n", a["accel"].get<std::string>(),
                                  a["failed"].get<std::string>());
                continue;
            }
            const auto cell = [](const nlohmann::json& v) {
                return v.is_null() ? std::string("n/a") : fmt::format("{:.2f}", v.get<double>());
            };
            md += fmt::format("| {} | {} | {} | {:.1f} | {:.0f} |\n", a["accel"].get<std::string>(), cell(a["n_it"]),
                              cell(a["n_tr"]), a["build_ms"].get<double>(), a["trace_ms"].get<double>());
        }
        md += "\n" + octreeMarkdown(scene["accels"]);
    }
    return md;
}

struct SpdOptions {
    EnvOptions env;
    std::vector<std::string> scenes;
    std::string accels;
    std::string out = "out/spd";
    double jobTimeout = 0;
    ChildJob child;
};

void addSpdOptions(CLI::App& command, SpdOptions& options) {
    addEnvOptions(command, options.env);
    addThreadsOption(command, options.env);
    command.add_option("scenes", options.scenes, "NFF scene files (SPD scenes have their own viewpoint and lights)")
        ->required();
    command.add_option("--accel", options.accels,
                       "comma-separated NAME or NAME:Key=value:... (default: ASDS::type); the first one's invariants "
                       "are compared with Havran's");
    command.add_option("--out", options.out, "output folder: spd.json, spd.md, SCENE.ACCEL.png")->capture_default_str();
    addJobTimeoutOption(command, options.jobTimeout);
    addChildJobOptions(command, options.child);
}

// An spd run: its structures, the env every scene starts from, Havran's figures and the rules.
struct SpdRun {
    const SpdOptions& options;
    std::filesystem::path out;
    std::vector<AccelConfig> configs;
    Env base;
    std::map<std::string, HavranScene> havran;
    SpdRules rules;

    Env sceneEnv(size_t s) const {
        Env env = base;
        env.set(keys::Scene::file, std::filesystem::absolute(options.scenes[s]).string(), "bvhlab spd");
        return env;
    }

    bool twoSided(const Scene& scene) const {
        const std::vector<std::string> names = splitCommaList(base.get(keys::Spd::twoSidedScenes));
        return std::find(names.begin(), names.end(), scene.name) != names.end();
    }

    // One job, in a process of its own: structure `c` on scene `s`, built, traced, its image written.
    nlohmann::json runJob(size_t s, size_t c) {
        const Env env = sceneEnv(s);
        const Scene scene = loadSceneFor(env);
        rules.twoSided = twoSided(scene);
        const AccelConfig& config = configs[c];
        Progress progress;
        const Env accelEnv = accelConfigEnv(config, env);
        progress.phase(fmt::format("{} {}: building", scene.name, config.label));
        auto accel = createAccelerator(config.name, accelEnv);
        const BuildStats build = [&] {
            const BuildWatch watch(fmt::format("{} on {}", config.label, scene.name));
            return timedBuild(*accel, scene.primitives());
        }();
        const uint64_t rows = uint64_t(scene.camera ? scene.camera->height + 1 : 0);
        progress.phase(fmt::format("{} {}: tracing", scene.name, config.label), rows);
        Framebuffer fb(scene.camera ? scene.camera->width : 1, scene.camera ? scene.camera->height : 1);
        const SpdResult result = traceSpd(scene, *accel, rules, fb, [&](uint64_t rays) { progress.advance(1, rays); });
        progress.finish();
        writePng(out / fmt::format("{}.{}.png", scene.name, labelAsFileName(config.label)), fb);
        // The figures after the trace: a structure's per-ray figures (an octree's N_ETS)
        // count the queries since its build.
        BuildStats traced = build;
        traced.figures = statisticsOf(*accel).figures;
        nlohmann::json havranColumn;
        if (const auto column = havranOctreeColumn(config, accelEnv); column && havran.count(scene.name))
            havranColumn = havranOctreeJson(havran.at(scene.name), column->first, column->second);
        return accelJson(config.label, traced, result, accel->hasCounters(), std::move(havranColumn));
    }

    // The job a child process was given, "S/C".
    nlohmann::json runChildJob(const std::string& job) {
        const size_t slash = job.find('/');
        size_t s = 0, c = 0;
        if (slash == std::string::npos || !parseNumber(std::string_view(job).substr(0, slash), s) ||
            !parseNumber(std::string_view(job).substr(slash + 1), c) || s >= options.scenes.size() ||
            c >= configs.size())
            throw InputError(fmt::format("{} {}: not a job of this spd run", kChildJobOption, job));
        return runJob(s, c);
    }

    // Scene `s` with Havran's figures for it and each structure's job, run in a process of its
    // own; `failed` counts the jobs that failed.
    nlohmann::json sceneResults(size_t s, size_t& failed) const {
        const Scene scene = loadSceneFor(sceneEnv(s));
        nlohmann::json sceneJson = {
            {"scene", scene.name}, {"two_sided", twoSided(scene)}, {"accels", nlohmann::json::array()}};
        if (const auto it = havran.find(scene.name); it != havran.end()) {
            const HavranScene& h = it->second;
            sceneJson["havran"]["invariants"] = h.invariants;
            for (const auto& [key, best] : {std::pair{"best_grid", h.bestGrid}, std::pair{"best_octree", h.bestOctree}})
                sceneJson["havran"][key] =
                    best ? nlohmann::json{{"n_it", best->nIt}, {"n_ts", best->nTs}} : nlohmann::json();
        } else {
            sceneJson["havran"] = nlohmann::json::object();
        }
        for (size_t c = 0; c < configs.size(); ++c) {
            const JobOutcome outcome = runJobInChild(fmt::format("{}/{}", s, c), options.jobTimeout);
            if (outcome.passed()) {
                sceneJson["accels"].push_back(outcome.result);
                continue;
            }
            ++failed;
            fmt::print(stderr, "{} {}: failed: {}\n", scene.name, configs[c].label, outcome.failure());
            sceneJson["accels"].push_back({{"accel", configs[c].label}, {"failed", outcome.failure()}});
        }
        return sceneJson;
    }
};

SpdRun prepareSpdRun(SpdOptions& options) {
    const std::filesystem::path out =
        options.child.isChild() ? std::filesystem::path(options.out) : prepareOutputFolder(options.out);
    std::vector<AccelConfig> configs = parseAccelConfigList(options.accels);
    nameAccelerators(configs, options.env);
    const Env base = chooseScene("", "", options.env).load(options.env);
    if (configs.empty()) configs = parseAccelConfigList(base.get(keys::ASDS::type));
    checkAccelConfigs(configs, base);
    const std::filesystem::path reference = base.get(keys::Spd::reference);
    if (!std::filesystem::is_directory(reference))
        throw InputError(
            fmt::format("Havran's statistics (havran_stats_grids.txt, havran_stats_octrees.txt): "
                        "no folder {}; {}",
                        reference.string(), base.howToSet(keys::Spd::reference)));
    auto havran = readHavranReference(reference);
    SpdRules rules;
    rules.maxDepth = base.get(keys::Spd::maxDepth);
    rules.threads = base.get(keys::SetRayTracing::threads);
    return SpdRun{options, out, std::move(configs), base, std::move(havran), rules};
}

// The run the options ask for; returns how many of its jobs failed.
size_t runSpd(SpdOptions& options) {
    SpdRun run = prepareSpdRun(options);
    if (options.child.isChild()) {
        options.child.run([&] { return run.runChildJob(options.child.job); });
        return 0;
    }
    nlohmann::json results = {{"provenance", provenanceJson()},
                              {"run", runJson()},
                              {"rules", {{"max_depth", run.rules.maxDepth}}},
                              {"scenes", nlohmann::json::array()}};
    size_t failed = 0;
    for (size_t s = 0; s < options.scenes.size(); ++s) results["scenes"].push_back(run.sceneResults(s, failed));
    results["failed_jobs"] = failed;
    writeFileAtomically(run.out / "spd.json", results.dump(2) + "\n");
    const std::string md = markdown(results);
    writeFileAtomically(run.out / "spd.md", md);
    fmt::print("{}", md);
    fmt::print(stderr, "wrote {}/spd.{{json,md}} and the images\n", run.out.string());
    if (failed) fmt::print(stderr, "spd: {} failed jobs\n", failed);
    return failed;
}

}  // namespace

void addSpdCommand(CLI::App& app) {
    auto options = std::make_shared<SpdOptions>();
    CLI::App* command = app.add_subcommand(
        "spd", "trace SPD scenes by the SPD rules; Havran's ray invariants and N_IT, N_TS beside his (DIR/spd.md)");
    addSpdOptions(*command, *options);
    command->callback([options] { runJobsGuarded([&] { return runSpd(*options); }); });
}

}  // namespace bvhlab
