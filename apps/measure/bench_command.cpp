// `bvhlab bench`: build time and query time of several structures on several scenes, each as a
// median of repeated runs and as a ratio to Embree measured in the same run (the machine is
// shared and noisy: absolute times drift, ratios hold). The yardstick is embree-bare, Embree as
// its users call it (rays converted once, a bare rtcIntersect1 loop); embree and embree-robust
// go through our interface, as every structure of ours does. A benchmark, not a test.
#include "accel/registry.h"
#include "apps/common/accel_config.h"
#include "apps/common/cli_common.h"
#include "apps/common/commands.h"
#include "apps/common/program_keys.h"
#include "apps/common/scene_list.h"
#include "apps/common/timing.h"
#include "apps/measure/ray_sets.h"
#include "framework/config/common_keys.h"
#include "framework/core/error.h"
#include "framework/core/parse_number.h"
#include "framework/core/timed_build.h"
#include "framework/render/renderer.h"
#include "framework/report/provenance.h"

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

// One structure of the contest, with what the rounds measured.
struct Contender {
    AccelConfig config;
    Env env{programKeys()};  // the scene's, with the config's overrides and the thread count
    std::unique_ptr<Accelerator> accel;
    BuildStats stats;
    std::vector<double> buildMs;                 // one per round
    std::vector<std::vector<double>> usPerQuery; // per ray set: one per round
    std::vector<QueryCounters> counters;         // per ray set: of the first round
};

struct NamedRaySet {
    const char* name;
    const std::vector<Ray>* rays;
    bool anyHit;
};

// Median over rounds of the ratio of two series measured round by round.
double pairedRatio(const std::vector<double>& values, const std::vector<double>& reference) {
    std::vector<double> ratios;
    for (size_t i = 0; i < values.size(); ++i)
        if (reference[i] > 0) ratios.push_back(values[i] / reference[i]);
    return median(ratios);
}

// Every structure of one scene at one thread count, measured in rounds: a round builds each
// structure once, then traces each ray set once with each structure, always in the same order.
// A slowdown of the shared machine thus hits all structures of a round alike, and the medians
// of the per-round ratios to Embree hold where absolute times drift by tens of percent.
std::vector<nlohmann::json> measureRounds(const Scene& scene, const RaySets& rays, const Env& sceneEnv,
                                          const std::vector<AccelConfig>& configs, int threads, int builds,
                                          int passes) {
    const NamedRaySet raySets[] = {{"primary", &rays.primary, false},
                                   {"shadow", &rays.shadow, true},
                                   {"incoherent", &rays.incoherent, true}};
    std::vector<Contender> contenders(configs.size());
    for (size_t c = 0; c < configs.size(); ++c) {
        Contender& k = contenders[c];
        k.config = configs[c];
        k.env = accelConfigEnv(k.config, sceneEnv);
        k.env.set(keys::SetRayTracing::threads, std::to_string(threads), "bvhlab bench --threads");
        k.usPerQuery.resize(std::size(raySets));
        k.counters.resize(std::size(raySets));
    }
    tbb::task_arena arena(threads);
    for (int round = 0; round < builds; ++round) {
        for (Contender& k : contenders) {
            k.accel.reset();  // the new structure replaces the old one, not beside it
            k.accel = createAccelerator(k.config.name, k.env);
            arena.execute([&] { k.stats = timedBuild(*k.accel, scene.primitives()); });
            k.buildMs.push_back(k.stats.buildMs);
        }
    }
    auto find = [&](const char* label) -> Contender& {
        return *std::find_if(contenders.begin(), contenders.end(), [&](const Contender& k) { return k.config.label == label; });
    };
    // embree-bare: the last build of `embree` queried as Embree's users do (NativeRayBatch), a
    // contender of its own in every round; its build is embree's (the same calls).
    Contender bare;
    bare.config.label = "embree-bare";
    bare.stats = find("embree").stats;
    bare.buildMs = find("embree").buildMs;
    bare.usPerQuery.resize(std::size(raySets));
    bare.counters.resize(std::size(raySets));
    std::vector<std::unique_ptr<NativeRayBatch>> bareRays;
    for (const NamedRaySet& set : raySets) bareRays.push_back(find("embree").accel->prepareNativeBatch(*set.rays));

    for (size_t set = 0; set < std::size(raySets); ++set) {
        for (int round = 0; round < passes; ++round) {
            for (Contender& k : contenders) {
                const PassResult r = tracePasses(*k.accel, *raySets[set].rays, raySets[set].anyHit, threads, 1);
                k.usPerQuery[set].push_back(r.usPerQuery);
                if (round == 0) k.counters[set] = r.counters;
            }
            const PassResult r = traceNativePasses(*bareRays[set], raySets[set].anyHit, threads, 1);
            bare.usPerQuery[set].push_back(r.usPerQuery);
            if (round == 0) bare.counters[set] = r.counters;
        }
    }
    contenders.push_back(std::move(bare));
    auto optional = [](const auto& v) { return v ? nlohmann::json(*v) : nlohmann::json(); };
    std::vector<nlohmann::json> rows;
    for (const Contender& k : contenders) {
        const bool counted = k.accel && k.accel->hasCounters();
        nlohmann::json row = {{"scene", scene.name},
                              {"accel", k.config.label},
                              {"threads", threads},
                              {"prims", scene.triangleCount()},
                              {"build_ms", median(k.buildMs)},
                              {"build_ms_all", k.buildMs},
                              {"nodes", optional(k.stats.nodes)},
                              {"leaves", optional(k.stats.leaves)},
                              {"sah", k.stats.sah ? nlohmann::json(k.stats.sah->cost) : nlohmann::json()},
                              {"epo", optional(k.stats.epo)},
                              {"leaf_sizes", k.stats.leafSizes.empty() ? nlohmann::json() : nlohmann::json(k.stats.leafSizes)},
                              {"bytes", optional(k.stats.bytes)}};
        for (size_t set = 0; set < std::size(raySets); ++set) {
            const double q = std::max<double>(1.0, double(k.counters[set].queries));
            row[raySets[set].name] = {
                {"t_r_us", median(k.usPerQuery[set])},
                {"t_r_us_all", k.usPerQuery[set]},
                {"queries", k.counters[set].queries},
                {"n_it", counted ? nlohmann::json(double(k.counters[set].intersectionTests) / q) : nlohmann::json()},
                {"n_tr", counted ? nlohmann::json(double(k.counters[set].traversalSteps) / q) : nlohmann::json()}};
        }
        // ratio_to_embree-bare, ratio_to_embree and ratio_to_embree-robust: medians of the
        // per-round ratios.
        for (const char* label : {"embree-bare", "embree", "embree-robust"}) {
            const Contender& ref = find(label);
            nlohmann::json ratios = {{"build", pairedRatio(k.buildMs, ref.buildMs)}};
            for (size_t set = 0; set < std::size(raySets); ++set) {
                ratios[raySets[set].name] = raySets[set].rays->empty()
                                                ? nlohmann::json()
                                                : nlohmann::json(pairedRatio(k.usPerQuery[set], ref.usPerQuery[set]));
            }
            row[std::string("ratio_to_") + label] = ratios;
        }
        rows.push_back(std::move(row));
    }
    return rows;
}

std::string numberOrNa(const nlohmann::json& v, const char* format) {
    return v.is_null() ? "n/a" : fmt::format(fmt::runtime(format), v.get<double>());
}

// One line per scene x threads x structure, then the geometric means of the ratios. xE is the
// ratio to embree-bare (Embree as its users call it), xER to embree-robust (through our interface).
std::string benchTable(const nlohmann::json& results) {
    size_t accelWidth = 14;
    for (const nlohmann::json& row : results["rows"]) accelWidth = std::max(accelWidth, row["accel"].get<std::string>().size());
    std::string out = fmt::format("{:<16} {:>3} {:<{}} {:>9} {:>6} {:>8} {:>6} {:>6} {:>8} {:>6} {:>6} {:>8} {:>6} {:>6} "
                                  "{:>6} {:>6} {:>8} {:>7} {:>7}\n",
                                  "scene", "thr", "accel", accelWidth, "T_B ms", "xE", "prim us", "xE", "xER", "shad us", "xE",
                                  "xER", "incoh us", "xE", "xER", "N_IT", "N_TR", "SAH", "EPO", "MB");
    std::map<std::string, std::vector<nlohmann::json>> byConfig;
    for (const nlohmann::json& row : results["rows"]) {
        const nlohmann::json& e = row["ratio_to_embree-bare"];
        const nlohmann::json& er = row["ratio_to_embree-robust"];
        out += fmt::format("{:<16} {:>3} {:<{}} {:>9.1f} {:>6} {:>8.3f} {:>6} {:>6} {:>8.3f} {:>6} {:>6} "
                           "{:>8.3f} {:>6} {:>6} {:>6} {:>6} {:>8} {:>7} {:>7}\n",
                           row["scene"].get<std::string>(), row["threads"].get<int>(), row["accel"].get<std::string>(),
                           accelWidth, row["build_ms"].get<double>(), numberOrNa(e["build"], "{:.2f}"),
                           row["primary"]["t_r_us"].get<double>(), numberOrNa(e["primary"], "{:.2f}"),
                           numberOrNa(er["primary"], "{:.2f}"), row["shadow"]["t_r_us"].get<double>(),
                           numberOrNa(e["shadow"], "{:.2f}"), numberOrNa(er["shadow"], "{:.2f}"),
                           row["incoherent"]["t_r_us"].get<double>(), numberOrNa(e["incoherent"], "{:.2f}"),
                           numberOrNa(er["incoherent"], "{:.2f}"), numberOrNa(row["primary"]["n_it"], "{:.1f}"),
                           numberOrNa(row["primary"]["n_tr"], "{:.1f}"), numberOrNa(row["sah"], "{:.2f}"),
                           numberOrNa(row["epo"], "{:.2f}"), row["bytes"].is_null() ? "n/a" : fmt::format("{:.1f}", row["bytes"].get<double>() / 1048576.0));
        byConfig[fmt::format("{} threads={}", row["accel"].get<std::string>(), row["threads"].get<int>())].push_back(row);
    }
    out += "\ngeometric means over scenes of the ratios to embree-bare (embree-robust):\n";
    for (const auto& [config, rows] : byConfig) {
        out += fmt::format("  {:<{}}", config, accelWidth + 14);
        for (const char* kind : {"build", "primary", "shadow", "incoherent"}) {
            double logE = 0, logER = 0;
            int n = 0;
            for (const nlohmann::json& row : rows)
                if (!row["ratio_to_embree-bare"][kind].is_null() && !row["ratio_to_embree-robust"][kind].is_null()) {
                    logE += std::log(row["ratio_to_embree-bare"][kind].get<double>());
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
    command->add_option("--scenes", options->scenes, "scene env files, .list files or scene files (default env/scenes.list)");
    command->add_option("--accel", options->accels,
                        "comma-separated NAME or NAME:Key=value:... (embree, embree-robust and embree-bare are always added)")
        ->capture_default_str();
    command->add_option("--threads", options->threads, "threads N (0 = all hardware threads), or a comma-separated list of them to measure each")
        ->capture_default_str();
    command->add_option("--builds", options->builds, "builds per structure (median)")->capture_default_str()->check(CLI::Range(1, 1000));
    command->add_option("--passes", options->passes, "passes over each ray set (median)")->capture_default_str()->check(CLI::Range(1, 1000));
    command->add_option("--out", options->out, "JSON results")->capture_default_str();
    command->callback([options] {
        const int code = runGuarded([&] {
            std::vector<AccelConfig> configs = parseAccelConfigList(options->accels);
            for (const char* reference : {"embree", "embree:Embree::robust=true"})
                if (std::none_of(configs.begin(), configs.end(), [&](const AccelConfig& c) { return c.label == parseAccelConfig(reference).label; }))
                    configs.push_back(parseAccelConfig(reference));
            checkAccelConfigs(configs, options->env.load());
            std::vector<int> threadCounts;
            for (const std::string& item : splitCommaList(options->threads)) {
                int t = -1;
                if (!parseNumber(item, t) || t < 0 || t > 1024)
                    throw InputError(fmt::format("--threads {}: '{}' is not a thread count 0..1024 (0 = all)",
                                                 options->threads, item));
                threadCounts.push_back(t > 0 ? t : tbb::info::default_concurrency());
            }
            if (threadCounts.empty()) throw InputError("--threads: no thread count given");

            nlohmann::json results = {{"provenance", provenanceJson()},
                                      {"builds", options->builds},
                                      {"passes", options->passes},
                                      {"rows", nlohmann::json::array()}};
            const std::vector<SceneArgument> scenes = expandSceneList(options->scenes, options->env);
            const std::filesystem::path out = prepareOutputFile(options->out);
            Progress progress;
            for (size_t s = 0; s < scenes.size(); ++s) {
                const Env env = scenes[s].load(options->env);
                const Scene scene = loadSceneFor(env);
                const RaySets rays = [&] {
                    auto reference = createAccelerator("embree", env);
                    reference->build(scene.primitives());
                    return sceneRaySets(scene, env, *reference);
                }();
                progress.phase(fmt::format("[{}/{}] {}: {} primary, {} shadow, {} incoherent rays", s + 1, scenes.size(),
                                           scene.name, rays.primary.size(), rays.shadow.size(), rays.incoherent.size()));

                for (int threads : threadCounts) {
                    for (nlohmann::json& row : measureRounds(scene, rays, env, configs, threads, options->builds,
                                                             options->passes)) {
                        fmt::print(stderr, "  {} threads={} {}: build {:.1f} ms, primary {:.3f} us/query ({:.2f}x embree-bare)\n",
                                   scene.name, threads, row["accel"].get<std::string>(), row["build_ms"].get<double>(),
                                   row["primary"]["t_r_us"].get<double>(),
                                   row["ratio_to_embree-bare"]["primary"].is_null() ? 0.0
                                                                                    : row["ratio_to_embree-bare"]["primary"].get<double>());
                        results["rows"].push_back(std::move(row));
                    }
                }
            }
            std::ofstream(out) << results.dump(2) << "\n";
            fmt::print("{}", benchTable(results));
            fmt::print(stderr, "wrote {}\n", out.string());
        });
        if (code != 0) throw CLI::RuntimeError(code);
    });
}

}  // namespace bvhlab
