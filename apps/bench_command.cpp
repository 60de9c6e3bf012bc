// `bvhlab bench`: build time and query time of several structures on several scenes, each as a
// median of repeated runs and as a ratio to Embree measured in the same run (the machine is
// shared and noisy: absolute times drift, ratios hold). A benchmark, not a test.
#include "accel/registry.h"
#include "apps/accel_config.h"
#include "apps/cli_common.h"
#include "apps/commands.h"
#include "apps/scene_list.h"
#include "apps/timing.h"
#include "framework/provenance.h"
#include "framework/ray_sets.h"
#include "framework/renderer.h"

#include <fmt/core.h>
#include <nlohmann/json.hpp>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <sstream>

namespace bvhlab {
namespace {

nlohmann::json passJson(const PassResult& r, bool hasCounters) {
    const double q = std::max<double>(1.0, double(r.counters.queries));
    return {{"t_r_us", r.usPerQuery},
            {"queries", r.counters.queries},
            {"n_it", hasCounters ? nlohmann::json(r.counters.intersectionTests / q) : nlohmann::json()},
            {"n_tr", hasCounters ? nlohmann::json(r.counters.traversalSteps / q) : nlohmann::json()}};
}

// Builds `config` `builds` times (median time) and traces every ray set `passes` times.
nlohmann::json measure(const Scene& scene, const RaySets& rays, const Env& sceneEnv, const AccelConfig& config,
                       int threads, int builds, int passes) {
    Env env = sceneEnv;
    for (const std::string& o : config.overrides) env.setOverride(o);
    env.setOverride(fmt::format("SetRayTracing::threads={}", threads));
    std::vector<double> buildMs;
    std::unique_ptr<Accelerator> accel;
    BuildStats stats;
    tbb::task_arena arena(threads);
    for (int b = 0; b < builds; ++b) {
        accel.reset();  // one structure (and one Embree device) alive at a time
        accel = createAccelerator(config.name, env);
        arena.execute([&] { stats = accel->build(scene.primitives()); });
        buildMs.push_back(stats.buildMs);
    }
    const bool counted = accel->hasCounters();
    auto optional = [](const auto& v) { return v ? nlohmann::json(*v) : nlohmann::json(); };
    return {{"scene", scene.name},
            {"accel", config.label},
            {"threads", threads},
            {"prims", scene.triangleCount()},
            {"build_ms", median(buildMs)},
            {"build_ms_all", buildMs},
            {"nodes", optional(stats.nodes)},
            {"leaves", optional(stats.leaves)},
            {"sah", stats.sah ? nlohmann::json(stats.sah->cost) : nlohmann::json()},
            {"bytes", optional(stats.bytes)},
            {"primary", passJson(tracePasses(*accel, rays.primary, false, threads, passes), counted)},
            {"shadow", passJson(tracePasses(*accel, rays.shadow, true, threads, passes), counted)},
            {"incoherent", passJson(tracePasses(*accel, rays.incoherent, true, threads, passes), counted)}};
}

// ratio_to_embree and ratio_to_embree-robust: build time and T_R divided by Embree's, same run.
void addRatios(std::map<std::string, nlohmann::json>& rows) {
    for (auto& [label, row] : rows)
        for (const char* ref : {"embree", "embree-robust"}) {
            const nlohmann::json& r = rows.at(ref);
            nlohmann::json ratios = {{"build", row["build_ms"].get<double>() / r["build_ms"].get<double>()}};
            for (const char* kind : {"primary", "shadow", "incoherent"}) {
                const double reference = r[kind]["t_r_us"].get<double>();
                ratios[kind] = reference > 0 ? nlohmann::json(row[kind]["t_r_us"].get<double>() / reference) : nlohmann::json();
            }
            row[std::string("ratio_to_") + ref] = ratios;
        }
}

std::string numberOrNa(const nlohmann::json& v, const char* format) {
    return v.is_null() ? "n/a" : fmt::format(fmt::runtime(format), v.get<double>());
}

// One line per scene x threads x structure, then the geometric means of the ratios.
std::string benchTable(const nlohmann::json& results) {
    std::string out = fmt::format("{:<16} {:>3} {:<14} {:>9} {:>6} {:>8} {:>6} {:>6} {:>8} {:>6} {:>6} {:>8} {:>6} {:>6} "
                                  "{:>6} {:>6} {:>8} {:>7}\n",
                                  "scene", "thr", "accel", "T_B ms", "xE", "prim us", "xE", "xER", "shad us", "xE",
                                  "xER", "incoh us", "xE", "xER", "N_IT", "N_TR", "SAH", "MB");
    std::map<std::string, std::vector<nlohmann::json>> byConfig;
    for (const nlohmann::json& row : results["rows"]) {
        const nlohmann::json& e = row["ratio_to_embree"];
        const nlohmann::json& er = row["ratio_to_embree-robust"];
        out += fmt::format("{:<16} {:>3} {:<14} {:>9.1f} {:>6} {:>8.3f} {:>6} {:>6} {:>8.3f} {:>6} {:>6} "
                           "{:>8.3f} {:>6} {:>6} {:>6} {:>6} {:>8} {:>7}\n",
                           row["scene"].get<std::string>(), row["threads"].get<int>(), row["accel"].get<std::string>(),
                           row["build_ms"].get<double>(), numberOrNa(e["build"], "{:.2f}"),
                           row["primary"]["t_r_us"].get<double>(), numberOrNa(e["primary"], "{:.2f}"),
                           numberOrNa(er["primary"], "{:.2f}"), row["shadow"]["t_r_us"].get<double>(),
                           numberOrNa(e["shadow"], "{:.2f}"), numberOrNa(er["shadow"], "{:.2f}"),
                           row["incoherent"]["t_r_us"].get<double>(), numberOrNa(e["incoherent"], "{:.2f}"),
                           numberOrNa(er["incoherent"], "{:.2f}"), numberOrNa(row["primary"]["n_it"], "{:.1f}"),
                           numberOrNa(row["primary"]["n_tr"], "{:.1f}"), numberOrNa(row["sah"], "{:.2f}"),
                           row["bytes"].is_null() ? "n/a" : fmt::format("{:.1f}", row["bytes"].get<double>() / 1048576.0));
        byConfig[fmt::format("{} threads={}", row["accel"].get<std::string>(), row["threads"].get<int>())].push_back(row);
    }
    out += "\ngeometric means over scenes of the ratios to embree (embree-robust):\n";
    for (const auto& [config, rows] : byConfig) {
        out += fmt::format("  {:<28}", config);
        for (const char* kind : {"build", "primary", "shadow", "incoherent"}) {
            double logE = 0, logER = 0;
            int n = 0;
            for (const nlohmann::json& row : rows)
                if (!row["ratio_to_embree"][kind].is_null() && !row["ratio_to_embree-robust"][kind].is_null()) {
                    logE += std::log(row["ratio_to_embree"][kind].get<double>());
                    logER += std::log(row["ratio_to_embree-robust"][kind].get<double>());
                    ++n;
                }
            out += n ? fmt::format("  {} {:.2f} ({:.2f})", kind, std::exp(logE / n), std::exp(logER / n)) : "";
        }
        out += "\n";
    }
    return out;
}

}  // namespace

void addBenchCommand(CLI::App& app) {
    struct Options {
        EnvOptions env;
        std::vector<std::string> scenes;
        std::string accels = "tdbvh,sahbvh,embree,embree:Embree::robust=true";
        std::string threads = "1,0";
        int builds = 5, passes = 5;
        std::string out = "out/bench.json";
    };
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand("bench", "time builds and queries against Embree (medians, ratios)");
    options->env.addTo(*command);
    command->add_option("--scenes", options->scenes, "scene env files or .list files (default env/scenes.list)");
    command->add_option("--accel", options->accels, "comma-separated NAME or NAME:Key=value:... (embree is always added)")
        ->capture_default_str();
    command->add_option("--threads", options->threads, "comma-separated thread counts; 0 = all hardware threads")
        ->capture_default_str();
    command->add_option("--builds", options->builds, "builds per structure (median)")->capture_default_str()->check(CLI::Range(1, 1000));
    command->add_option("--passes", options->passes, "passes over each ray set (median)")->capture_default_str()->check(CLI::Range(1, 1000));
    command->add_option("--out", options->out, "JSON results")->capture_default_str();
    command->callback([options] {
        const int code = runGuarded([&] {
            std::vector<AccelConfig> configs;
            std::string item;
            for (std::stringstream in(options->accels); std::getline(in, item, ',');) configs.push_back(parseAccelConfig(item));
            for (const char* reference : {"embree", "embree:Embree::robust=true"})
                if (std::none_of(configs.begin(), configs.end(), [&](const AccelConfig& c) { return c.label == parseAccelConfig(reference).label; }))
                    configs.push_back(parseAccelConfig(reference));
            std::vector<int> threadCounts;
            for (std::stringstream in(options->threads); std::getline(in, item, ',');) {
                const int t = std::stoi(item);
                threadCounts.push_back(t > 0 ? t : tbb::info::default_concurrency());
            }

            nlohmann::json results = {{"provenance", provenanceJson()},
                                      {"builds", options->builds},
                                      {"passes", options->passes},
                                      {"rows", nlohmann::json::array()}};
            const std::vector<std::filesystem::path> sceneEnvs = expandSceneList(options->scenes);
            for (size_t s = 0; s < sceneEnvs.size(); ++s) {
                const Env env = options->env.load({sceneEnvs[s].string()});
                const Scene scene = loadSceneFor("", env);
                const Camera camera(resolveCamera(scene, env));
                const RenderSettings settings = RenderSettings::fromEnv(env, scene, camera.spec());
                const RaySets rays = [&] {
                    auto reference = createAccelerator("embree", env);
                    reference->build(scene.primitives());
                    return makeRaySets(scene, camera, settings.lights, *reference);
                }();
                fmt::print(stderr, "[{}/{}] {}: {} primary, {} shadow, {} incoherent rays\n", s + 1, sceneEnvs.size(),
                           scene.name, rays.primary.size(), rays.shadow.size(), rays.incoherent.size());

                for (int threads : threadCounts) {
                    std::map<std::string, nlohmann::json> rows;
                    for (const AccelConfig& config : configs) {
                        nlohmann::json row = measure(scene, rays, env, config, threads, options->builds, options->passes);
                        fmt::print(stderr, "  {} threads={} {}: build {:.1f} ms, primary {:.3f} us/query\n", scene.name,
                                   threads, config.label, row["build_ms"].get<double>(),
                                   row["primary"]["t_r_us"].get<double>());
                        rows[config.label] = std::move(row);
                    }
                    addRatios(rows);
                    for (const AccelConfig& config : configs) results["rows"].push_back(rows[config.label]);
                }
            }
            const std::filesystem::path out = options->out;
            if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
            std::ofstream(out) << results.dump(2) << "\n";
            fmt::print("{}", benchTable(results));
            fmt::print(stderr, "wrote {}\n", out.string());
        });
        if (code != 0) throw CLI::RuntimeError(code);
    });
}

}  // namespace bvhlab
