// `bvhlab bench`: build time and query time of several structures on several scenes, each as a
// median of repeated runs and as a ratio to Embree measured in the same run (the machine is
// shared and noisy: absolute times drift, ratios hold). Each structure is asked in one or both of
// two ways (--queries): single rays, one findNearest / isOccluded per ray, against embree-bare
// (Embree as its users call it: rays converted once, a bare rtcIntersect1 loop); and batches,
// findNearestBatch / isOccludedBatch per range of kQueryRange rays, against embree-batch (the same
// prepared rays through Embree's stream or packet API, whichever is faster). embree and
// embree-robust go through our interface, as every structure of ours does; nothing and
// nothing-guarded time a query that does nothing through it (nothing_accelerator.h), bare and
// behind the guard of a plugin's structure: the floor under every row. A benchmark, not a test.
// Each scene is a job in a process of its own (apps/runtime/child_job.h): a structure that
// crashes, throws or runs past --job-timeout fails its scene's job (all its structures share the
// rounds), a failed row with the reason, and the other scenes run. --isa-pairs times copies of
// the structures at one ISA against Embree at that ISA beside them (isa_pairs.h).
#include "accel/registry.h"
#include "apps/cli/command_line.h"
#include "apps/cli/commands.h"
#include "apps/measure/bench_resume.h"
#include "apps/measure/isa_pairs.h"
#include "apps/measure/nothing_accelerator.h"
#include "apps/runtime/accel_config.h"
#include "apps/runtime/atomic_write.h"
#include "apps/runtime/build_watch.h"
#include "apps/runtime/child_job.h"
#include "apps/runtime/comma_list.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/program_keys.h"
#include "apps/runtime/progress.h"
#include "apps/runtime/ray_sets.h"
#include "apps/runtime/run_record.h"
#include "apps/runtime/scene_list.h"
#include "apps/runtime/scene_loading.h"
#include "apps/runtime/timing.h"
#include "framework/config/common_keys.h"
#include "framework/core/error.h"
#include "framework/core/parse_number.h"
#include "framework/core/timed_build.h"
#include "framework/render/renderer.h"
#include "framework/report/build_stats_json.h"
#include "framework/report/provenance.h"
#include "framework/report/query_counters_json.h"

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <map>
#include <span>
#include <sstream>

namespace bvhlab {
namespace {

// A structure of the contest as --accel and --isa-pairs give it, at `isa`: "best" in the
// headline pair (its keys as given: by default the best ISA the CPU runs), else a pair's ISA.
struct ContestConfig {
    AccelConfig accel;
    std::string isa = "best";
};

// One structure of the contest: its builds, measured in rounds.
struct Structure {
    AccelConfig config;
    std::string isa = "best";
    Env env{programKeys()};  // the scene's, with the config's overrides and the thread count
    std::unique_ptr<Accelerator> accel;
    BuildStats stats;
    std::vector<double> buildMs;  // one per round
};

// The structures of the rows that measure the interface's own cost: a query that does nothing,
// bare and behind the guard every plugin's structure is called through (accel/plugins/guarded_accelerator.h).
const char* const kNothingRows[] = {"nothing", "nothing-guarded"};

std::unique_ptr<Accelerator> createFor(const Structure& k) {
    if (k.config.label == kNothingRows[0]) return std::make_unique<NothingAccelerator>();
    if (k.config.label == kNothingRows[1])
        return guardLikeAPlugin(std::make_unique<NothingAccelerator>(), "(bvhlab bench)", "nothing");
    return createAccelerator(k.config.name, k.env);
}

// Embree queried as its users do, at one ISA of the contest: the last build of `embree` (or of
// its copy at that ISA) with the rays prepared once per set outside the timing
// (NativeBatchApis: prepareNativeBatch, and for each of its batch APIs), the yardstick of the
// rows at that ISA.
struct EmbreeYardstick {
    std::string isa;
    const Structure* structure = nullptr;
    const NativeBatchApis* apis = nullptr;
    std::vector<std::string> batchApis;
    std::unique_ptr<NativeRayBatch> bare;                             // of the current ray set
    std::map<std::string, std::unique_ptr<NativeRayBatch>> prepared;  // likewise, per batch API
};

// One row of the results: a structure asked as `queries` says (or Embree through its own API:
// embree-bare, embree-batch), with what the rounds measured.
struct Contender {
    Contender(std::string label, QueryKind queries, const Structure* structure, EmbreeYardstick* native = nullptr)
        : label(std::move(label)), queries(queries), structure(structure), native(native) {}

    std::string label;
    QueryKind queries;
    const Structure* structure;                   // its builds; embree's for embree-bare and -batch
    EmbreeYardstick* native;                      // embree-bare and -batch's prepared rays; else null
    std::vector<std::vector<double>> usPerQuery;  // per ray set: one per round
    std::vector<QueryCounters> counters;          // per ray set: of the first round's counting pass
    // embree-batch: per ray set, each batch API's series and the one kept (the lowest median).
    std::vector<std::map<std::string, std::vector<double>>> byApi;
    std::vector<std::string> kept;
};

struct NamedRaySet {
    const std::vector<Ray>* rays;
    const RaySetQuery& asked;
};

// Median over rounds of the ratio of two series measured round by round.
double pairedRatio(const std::vector<double>& values, const std::vector<double>& reference) {
    std::vector<double> ratios;
    for (size_t i = 0; i < values.size(); ++i)
        if (reference[i] > 0) ratios.push_back(values[i] / reference[i]);
    return median(ratios);
}

// The yardstick of each kind of query: Embree as its users call it, ray by ray (a bare loop of
// rtcIntersect1) or in batches (the faster of its stream and packet APIs).
const char* yardstick(QueryKind kind) { return kind == QueryKind::Single ? "embree-bare" : "embree-batch"; }

// Every structure of the contest and the nothing rows, with the scene's env, its overrides and
// the thread count; not built yet.
std::vector<Structure> contestStructures(const std::vector<ContestConfig>& configs, const Env& sceneEnv, int threads) {
    std::vector<Structure> structures(configs.size() + std::size(kNothingRows));
    for (size_t c = 0; c < structures.size(); ++c) {
        Structure& k = structures[c];
        if (c < configs.size()) {
            k.config = configs[c].accel;
            k.isa = configs[c].isa;
            k.env = accelConfigEnv(k.config, sceneEnv);
        } else {
            k.config.label = kNothingRows[c - configs.size()];
        }
        k.env.set(keys::SetRayTracing::threads, std::to_string(threads), "bvhlab bench --threads");
    }
    return structures;
}

// Builds every structure once a round, `builds` rounds; the last build of each is kept.
void buildInRounds(std::vector<Structure>& structures, const Scene& scene, tbb::task_arena& arena, int builds) {
    for (int round = 0; round < builds; ++round) {
        for (Structure& k : structures) {
            k.accel.reset();  // the new structure replaces the old one, not beside it
            k.accel = createFor(k);
            const BuildWatch watch(fmt::format("{} on {}", k.config.label, scene.name));
            arena.execute([&] { k.stats = timedBuild(*k.accel, scene.primitives()); });
            k.buildMs.push_back(k.stats.buildMs);
        }
    }
}

// embree-bare and embree-batch at each ISA: contenders of their own in every round, their
// build embree's at that ISA.
std::vector<EmbreeYardstick> embreeYardsticks(const std::vector<Structure>& structures) {
    std::vector<EmbreeYardstick> yardsticks;
    for (const Structure& k : structures) {
        if (k.config.label != labelAtIsa("embree", k.isa)) continue;
        EmbreeYardstick& y = yardsticks.emplace_back();
        y.isa = k.isa;
        y.structure = &k;
        y.apis = dynamic_cast<const NativeBatchApis*>(k.accel.get());
        if (!y.apis) throw std::logic_error("bvhlab bench: embree has no NativeBatchApis");
        y.batchApis = y.apis->batchApis();  // fewer packets at a lower ISA
    }
    return yardsticks;
}

bool isBatchYardstick(const Contender& k) { return k.native && k.queries == QueryKind::Batch; }

// Every structure through each kind of query, and Embree's own APIs, in the order of every round.
std::vector<Contender> contestContenders(const std::vector<Structure>& structures,
                                         std::vector<EmbreeYardstick>& yardsticks, const std::vector<QueryKind>& kinds,
                                         size_t sets) {
    std::vector<Contender> contenders;
    for (QueryKind kind : kinds) {
        for (const Structure& k : structures) contenders.emplace_back(k.config.label, kind, &k);
        for (EmbreeYardstick& y : yardsticks)
            contenders.emplace_back(labelAtIsa(yardstick(kind), y.isa), kind, y.structure, &y);
    }
    for (Contender& k : contenders) {
        k.usPerQuery.resize(sets);
        k.counters.resize(sets);
        if (isBatchYardstick(k)) k.byApi.resize(sets);
    }
    return contenders;
}

// Traces ray set `set` with every contender once a round, `passes` rounds.
void traceInRounds(std::vector<Contender>& contenders, std::vector<EmbreeYardstick>& yardsticks, const NamedRaySet& s,
                   size_t set, const std::vector<QueryKind>& kinds, int threads, int passes) {
    // Embree's prepared rays of this set only (a copy per API, and another to reset from).
    const auto asked = [&](QueryKind kind) { return std::find(kinds.begin(), kinds.end(), kind) != kinds.end(); };
    for (EmbreeYardstick& y : yardsticks) {
        y.bare.reset();
        y.prepared.clear();
        if (asked(QueryKind::Single)) y.bare = y.apis->prepareNativeBatch(*s.rays);
        if (asked(QueryKind::Batch))
            for (const std::string& api : y.batchApis)
                y.prepared[api] = y.apis->prepareBatchApi(*s.rays, api, s.asked.coherence);
    }
    for (int round = 0; round < passes; ++round) {
        for (Contender& k : contenders) {
            PassResult r;
            if (isBatchYardstick(k)) {
                for (const std::string& api : k.native->batchApis) {
                    r = traceNativePasses(*k.native->prepared[api], s.asked.anyHit, threads, 1);
                    k.byApi[set][api].push_back(r.usPerQuery);
                }
            } else if (k.native) {
                r = traceNativePasses(*k.native->bare, s.asked.anyHit, threads, 1);
            } else {
                r = tracePasses(*k.structure->accel, *s.rays, s.asked.anyHit, s.asked.coherence, threads, 1, k.queries,
                                /*count=*/round == 0);
            }
            if (!isBatchYardstick(k)) k.usPerQuery[set].push_back(r.usPerQuery);
            if (round == 0) k.counters[set] = r.counters;
        }
    }
}

// embree-batch keeps, per ray set, the batch API with the lowest median.
void keepFastestApis(std::vector<Contender>& contenders) {
    for (Contender& k : contenders)
        for (size_t set = 0; set < k.byApi.size(); ++set) {
            const auto fastest =
                std::min_element(k.byApi[set].begin(), k.byApi[set].end(),
                                 [](const auto& a, const auto& b) { return median(a.second) < median(b.second); });
            k.kept.push_back(fastest->first);
            k.usPerQuery[set] = fastest->second;
        }
}

// A contender's row: its builds, its medians per ray set, and its ratios to the yardsticks.
nlohmann::json contenderRow(const Contender& k, const std::vector<Contender>& contenders, const Scene& scene,
                            std::span<const NamedRaySet> raySets, int threads) {
    auto find = [&](const std::string& label, QueryKind kind) -> const Contender* {
        const auto it = std::find_if(contenders.begin(), contenders.end(),
                                     [&](const Contender& c) { return c.label == label && c.queries == kind; });
        return it == contenders.end() ? nullptr : &*it;
    };
    const Structure& structure = *k.structure;
    const bool counted = !k.native && structure.accel->hasCounters();
    nlohmann::json row = {{"scene", scene.name},
                          {"accel", k.label},
                          {"isa", structure.isa},
                          {"queries", toString(k.queries)},
                          {"threads", threads},
                          {"prims", scene.triangleCount()},
                          {"build_ms", median(structure.buildMs)},
                          {"build_ms_all", structure.buildMs}};
    row.update(buildStatsJson(structure.stats));
    for (size_t set = 0; set < raySets.size(); ++set) {
        const double q = std::max<double>(1.0, double(k.counters[set].queries));
        row[raySets[set].asked.kind] = {{"t_r_us", median(k.usPerQuery[set])},
                                        {"t_r_us_all", k.usPerQuery[set]},
                                        {"queries", k.counters[set].queries}};
        row[raySets[set].asked.kind].update(queryCountersJson(k.counters[set], q, counted));
        if (!k.kept.empty()) {
            row["embree_batch_api"][raySets[set].asked.kind] = k.kept[set];
            for (const auto& [api, series] : k.byApi[set])
                row[raySets[set].asked.kind]["t_r_us_by_api"][api] = median(series);
        }
    }
    // Medians of the per-round ratios: to embree-bare and embree-batch (whichever this run
    // measured), and to embree and embree-robust asked as this row is; all at the row's ISA.
    const std::pair<const char*, QueryKind> references[] = {{"embree-bare", QueryKind::Single},
                                                            {"embree-batch", QueryKind::Batch},
                                                            {"embree", k.queries},
                                                            {"embree-robust", k.queries}};
    for (const auto& [name, kind] : references) {
        const std::string label = labelAtIsa(name, structure.isa);
        const Contender* ref = find(label, kind);
        if (!ref) continue;
        nlohmann::json ratios = {{"build", pairedRatio(structure.buildMs, ref->structure->buildMs)}};
        for (size_t set = 0; set < raySets.size(); ++set) {
            ratios[raySets[set].asked.kind] =
                raySets[set].rays->empty() ? nlohmann::json()
                                           : nlohmann::json(pairedRatio(k.usPerQuery[set], ref->usPerQuery[set]));
        }
        row["ratio_to_" + label] = ratios;
    }
    return row;
}

// Every structure of one scene at one thread count, measured in rounds: a round builds each
// structure once, then traces each ray set once with each contender (every structure through
// each kind of query, and Embree's own APIs), always in the same order. A slowdown of the shared
// machine thus hits all contenders of a round alike, and the medians of the per-round ratios to
// Embree hold where absolute times drift by tens of percent.
std::vector<nlohmann::json> measureRounds(const Scene& scene, const RaySets& rays, const Env& sceneEnv,
                                          const std::vector<ContestConfig>& configs,
                                          const std::vector<QueryKind>& kinds, int threads, int builds, int passes) {
    const NamedRaySet raySets[] = {
        {&rays.primary, kRaySetQueries[0]}, {&rays.shadow, kRaySetQueries[1]}, {&rays.incoherent, kRaySetQueries[2]}};
    constexpr size_t kSets = std::size(raySets);
    std::vector<Structure> structures = contestStructures(configs, sceneEnv, threads);
    tbb::task_arena arena(threads);
    buildInRounds(structures, scene, arena, builds);
    std::vector<EmbreeYardstick> yardsticks = embreeYardsticks(structures);
    std::vector<Contender> contenders = contestContenders(structures, yardsticks, kinds, kSets);
    for (size_t set = 0; set < kSets; ++set)
        traceInRounds(contenders, yardsticks, raySets[set], set, kinds, threads, passes);
    keepFastestApis(contenders);

    std::vector<nlohmann::json> rows;
    for (const Contender& k : contenders) rows.push_back(contenderRow(k, contenders, scene, raySets, threads));
    return rows;
}

std::string numberOrNa(const nlohmann::json& v, const char* format) {
    return v.is_null() ? "n/a" : fmt::format(fmt::runtime(format), v.get<double>());
}

// A row's ratios to `label`'s row (null where this run did not measure it).
const nlohmann::json& ratiosTo(const nlohmann::json& row, const std::string& label) {
    static const nlohmann::json none = {
        {"build", nullptr}, {"primary", nullptr}, {"shadow", nullptr}, {"incoherent", nullptr}};
    const auto it = row.find("ratio_to_" + label);
    return it == row.end() ? none : *it;
}

// The ISA of a row ("best" in the headline pair and in results from before --isa-pairs).
std::string isaOf(const nlohmann::json& row) { return row.value("isa", std::string("best")); }

// The yardstick of a row: embree-bare for single queries, embree-batch for batch queries, at the
// row's ISA.
std::string yardstickOf(const nlohmann::json& row) {
    return labelAtIsa(yardstick(row["queries"] == "single" ? QueryKind::Single : QueryKind::Batch), isaOf(row));
}

// The geometric means over scenes of each configuration's ratios (rows by "ACCEL QUERIES threads=N").
std::string geometricMeanLines(const std::map<std::string, std::vector<nlohmann::json>>& byConfig, size_t accelWidth) {
    std::string out =
        "\ngeometric means over scenes of the ratios to embree-bare (single rows) or embree-batch (batch rows), "
        "to embree-robust asked the same way in brackets:\n";
    for (const auto& [config, rows] : byConfig) {
        out += fmt::format("  {:<{}}", config, accelWidth + 21);
        for (const char* kind : {"build", "primary", "shadow", "incoherent"}) {
            double logE = 0, logER = 0;
            int n = 0;
            for (const nlohmann::json& row : rows) {
                const nlohmann::json& e = ratiosTo(row, yardstickOf(row))[kind];
                const nlohmann::json& er = ratiosTo(row, labelAtIsa("embree-robust", isaOf(row)))[kind];
                if (!e.is_null() && !er.is_null()) {
                    logE += std::log(e.get<double>());
                    logER += std::log(er.get<double>());
                    ++n;
                }
            }
            out += n ? fmt::format("  {} {:.2f} ({:.2f})", kind, std::exp(logE / n), std::exp(logER / n)) : "";
        }
        out += "\n";
    }
    return out;
}

// One line per scene x threads x structure x kind of query, then the geometric means of the
// ratios. xE is the ratio to the row's yardstick (embree-bare for single rows, embree-batch for
// batch rows: Embree as its users call it), xER to embree-robust asked the same way (through
// our interface); embree-batch's line ends with the API it kept per ray set. Only the rows of the
// structures in `shown` (what --accel chose, so that one plugin's comparison is not buried under
// the reference rows), then what each of them is: its own settings, its plugin.
std::string benchTable(const nlohmann::json& results, const std::vector<std::string>& shown) {
    const auto isShown = [&](const nlohmann::json& row) {
        return row.contains("accel") &&
               std::find(shown.begin(), shown.end(), row["accel"].get<std::string>()) != shown.end();
    };
    size_t accelWidth = 14;
    for (const nlohmann::json& row : results["rows"])
        if (isShown(row)) accelWidth = std::max(accelWidth, row["accel"].get<std::string>().size());
    std::string out = fmt::format(
        "{:<16} {:>3} {:<{}} {:<6} {:>9} {:>6} {:>8} {:>6} {:>6} {:>8} {:>6} {:>6} {:>8} {:>6} {:>6} "
        "{:>6} {:>6} {:>8} {:>7} {:>7}\n",
        "scene", "thr", "accel", accelWidth, "query", "T_B ms", "xE", "prim us", "xE", "xER", "shad us", "xE", "xER",
        "incoh us", "xE", "xER", "N_IT", "N_TR", "SAH", "EPO", "MB");
    std::map<std::string, std::vector<nlohmann::json>> byConfig;
    for (const nlohmann::json& row : results["rows"]) {
        if (row.contains("failed")) {
            out +=
                fmt::format("{:<16} failed: {}\n", row["scene"].get<std::string>(), row["failed"].get<std::string>());
            continue;
        }
        if (!isShown(row)) continue;
        const nlohmann::json& e = ratiosTo(row, yardstickOf(row));
        const nlohmann::json& er = ratiosTo(row, labelAtIsa("embree-robust", isaOf(row)));
        out += fmt::format(
            "{:<16} {:>3} {:<{}} {:<6} {:>9.1f} {:>6} {:>8.3f} {:>6} {:>6} {:>8.3f} {:>6} {:>6} "
            "{:>8.3f} {:>6} {:>6} {:>6} {:>6} {:>8} {:>7} {:>7}",
            row["scene"].get<std::string>(), row["threads"].get<int>(), row["accel"].get<std::string>(), accelWidth,
            row["queries"].get<std::string>(), row["build_ms"].get<double>(), numberOrNa(e["build"], "{:.2f}"),
            row["primary"]["t_r_us"].get<double>(), numberOrNa(e["primary"], "{:.2f}"),
            numberOrNa(er["primary"], "{:.2f}"), row["shadow"]["t_r_us"].get<double>(),
            numberOrNa(e["shadow"], "{:.2f}"), numberOrNa(er["shadow"], "{:.2f}"),
            row["incoherent"]["t_r_us"].get<double>(), numberOrNa(e["incoherent"], "{:.2f}"),
            numberOrNa(er["incoherent"], "{:.2f}"), numberOrNa(row["primary"]["n_it"], "{:.1f}"),
            numberOrNa(row["primary"]["n_tr"], "{:.1f}"), numberOrNa(row["sah"], "{:.2f}"),
            numberOrNa(row["epo"], "{:.2f}"),
            row["bytes"].is_null() ? "n/a" : fmt::format("{:.1f}", row["bytes"].get<double>() / 1048576.0));
        if (row.contains("embree_batch_api"))
            for (const char* set : {"primary", "shadow", "incoherent"})
                out += fmt::format("  {} {}", set, row["embree_batch_api"][set].get<std::string>());
        out += "\n";
        byConfig[fmt::format("{} {} threads={}", row["accel"].get<std::string>(), row["queries"].get<std::string>(),
                             row["threads"].get<int>())]
            .push_back(row);
    }
    out += geometricMeanLines(byConfig, accelWidth);
    if (results.contains("isa_pairs")) {
        const nlohmann::json& pairs = results["isa_pairs"];
        for (const std::string isa : pairs["isas"])
            out += fmt::format(
                "\nrows LABEL@{0}: BVH::isa={0} or Embree::isa={0}, their ratios to Embree's rows at {0} "
                "(embree-bare@{0}, embree-batch@{0}, embree-robust@{0}); the others at this CPU's best, {1}\n",
                isa, pairs["best"].get<std::string>());
        if (!pairs["note"].get<std::string>().empty()) out += fmt::format("\n{}\n", pairs["note"].get<std::string>());
    }
    if (results["scenes"].empty()) return out;
    out += "\nstructures, with their own settings:\n";
    const nlohmann::json& structures = results["scenes"].front()["result_key"]["structures"];
    for (const std::string& label : shown)
        if (structures.contains(label)) out += fmt::format("  {}: {}\n", label, describeStructure(structures[label]));
    std::vector<std::string> hidden;
    for (const nlohmann::json& row : results["rows"])
        if (row.contains("accel") && !isShown(row) &&
            std::find(hidden.begin(), hidden.end(), row["accel"]) == hidden.end())
            hidden.push_back(row["accel"].get<std::string>());
    if (!hidden.empty())
        out += fmt::format("the reference rows ({}) are in the JSON; --reference-rows shows them here\n",
                           fmt::join(hidden, ", "));
    return out;
}

struct BenchOptions {
    EnvOptions env;
    std::vector<std::string> scenes;
    std::string accels = "tdbvh,sahbvh,embree,embree:Embree::robust=true";
    std::string threads = "1,0";
    std::string queries = "single,batch";
    std::string isaPairs;
    int builds = 5, passes = 5;
    std::string out = "out/bench.json";
    bool fresh = false;
    bool referenceRows = false;
    double jobTimeout = 0;
    ChildJob child;
};

void addBenchOptions(CLI::App& command, BenchOptions& options) {
    addEnvOptions(command, options.env);
    addScenesOption(command, options.scenes, "", "env/scenes.list");
    command
        .add_option("--accel", options.accels,
                    "comma-separated NAME or NAME:Key=value:... (embree, embree-robust, embree-bare, embree-batch, "
                    "nothing and nothing-guarded are always added)")
        ->capture_default_str();
    command
        .add_option("--queries", options.queries,
                    "single (ray by ray, against embree-bare), batch (the batch calls, against embree-batch) or both, "
                    "comma-separated")
        ->capture_default_str();
    command.add_option("--isa-pairs", options.isaPairs,
                       "ISAs at which to time ours against Embree beside the headline pair (each at the best ISA the "
                       "CPU runs), comma-separated: avx2, avx512. Each structure that reads BVH::isa or Embree::isa "
                       "is timed again as LABEL@ISA with that key set, against Embree's rows at ISA; one that is the "
                       "CPU's best is the headline pair, timed once");
    command
        .add_option("--threads", options.threads,
                    "threads N (0 = all hardware threads), or a comma-separated list of them to measure each")
        ->capture_default_str();
    command.add_option("--builds", options.builds, "builds per structure (median)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    command.add_option("--passes", options.passes, "passes over each ray set (median)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    command.add_option("--out", options.out, "JSON results")->capture_default_str();
    command.add_flag("--reference-rows", options.referenceRows,
                     "show the reference rows in the table too (those --accel did not choose: Embree through our "
                     "interface and its own, the nothing rows); the JSON always has them");
    command.add_flag("--fresh", options.fresh,
                     "measure every scene again; without it, a scene whose rows --out holds with the same result key "
                     "(program, structures and their plugins, scene, rounds) is kept as a whole");
    addJobTimeoutOption(command, options.jobTimeout);
    addChildJobOptions(command, options.child);
}

// The structures of --accel with Embree through our interface added, named and checked.
std::vector<AccelConfig> benchConfigs(BenchOptions& options) {
    std::vector<AccelConfig> configs = parseAccelConfigList(options.accels);
    for (const char* reference : {"embree", "embree:Embree::robust=true"})
        if (std::none_of(configs.begin(), configs.end(),
                         [&](const AccelConfig& c) { return c.label == parseAccelConfig(reference).label; }))
            configs.push_back(parseAccelConfig(reference));
    for (const AccelConfig& c : configs)
        if (std::find(std::begin(kNothingRows), std::end(kNothingRows), c.label) != std::end(kNothingRows))
            throw InputError(fmt::format("--accel {}: the bench's own row of that name", c.label));
    nameAccelerators(configs, options.env);
    checkAccelConfigs(configs, options.env.load());
    return configs;
}

std::vector<int> parseThreadCounts(const std::string& text) {
    std::vector<int> threadCounts;
    for (const std::string& item : splitCommaList(text)) {
        int t = -1;
        if (!parseNumber(item, t) || t < 0 || t > 1024)
            throw InputError(fmt::format("--threads {}: '{}' is not a thread count 0..1024 (0 = all)", text, item));
        threadCounts.push_back(t > 0 ? t : tbb::info::default_concurrency());
    }
    if (threadCounts.empty()) throw InputError("--threads: no thread count given");
    return threadCounts;
}

std::vector<QueryKind> parseQueryKinds(const std::string& text) {
    std::vector<QueryKind> kinds;
    for (const std::string& item : splitCommaList(text)) {
        const QueryKind kind = item == "single" ? QueryKind::Single : QueryKind::Batch;
        if ((item != "single" && item != "batch") || std::find(kinds.begin(), kinds.end(), kind) != kinds.end())
            throw InputError(fmt::format("--queries {}: '{}' is not single or batch (or is given twice)", text, item));
        kinds.push_back(kind);
    }
    if (kinds.empty()) throw InputError("--queries: no kind of query given (single, batch)");
    return kinds;
}

// What a bench measures, from its options: every scene, each with every structure of the contest
// at every thread count and kind of query.
struct BenchPlan {
    IsaPairs pairs;
    std::vector<ContestConfig> contest;      // each structure, then its copies at the ISAs of --isa-pairs
    std::vector<AccelConfig> contestAccels;  // the same, for the result key
    std::vector<int> threadCounts;
    std::vector<QueryKind> kinds;
    std::vector<SceneArgument> scenes;
};

BenchPlan planBench(BenchOptions& options) {
    BenchPlan plan;
    const std::vector<AccelConfig> configs = benchConfigs(options);
    // Each structure, then its copies at the ISAs of --isa-pairs: the rows of a pair side by side.
    plan.pairs = parseIsaPairs(options.isaPairs);
    for (const AccelConfig& config : configs) {
        plan.contest.push_back({config, "best"});
        for (const std::string& isa : plan.pairs.isas)
            if (const std::optional<AccelConfig> copy = configAtIsa(config, isa)) plan.contest.push_back({*copy, isa});
    }
    for (const ContestConfig& c : plan.contest) plan.contestAccels.push_back(c.accel);
    plan.threadCounts = parseThreadCounts(options.threads);
    plan.kinds = parseQueryKinds(options.queries);
    plan.scenes = expandSceneList(options.scenes, options.env);
    // Every scene file looked for up front: a typo in the last one fails now, not as its job.
    for (const SceneArgument& scene : plan.scenes) sceneFileOf(scene.load(options.env));
    return plan;
}

// The job of scene `s`, in its own process: every structure at every thread count.
nlohmann::json measureBenchScene(const BenchOptions& options, const BenchPlan& plan, size_t s) {
    nlohmann::json rows = nlohmann::json::array();
    Progress progress;
    const Env env = plan.scenes[s].load(options.env);
    const Scene scene = loadSceneFor(env);
    const RaySets rays = [&] {
        auto reference = createAccelerator("embree", env);
        reference->build(scene.primitives());
        return sceneRaySets(scene, env, *reference);
    }();
    progress.phase(fmt::format("[{}/{}] {}: {} primary, {} shadow, {} incoherent rays", s + 1, plan.scenes.size(),
                               scene.name, rays.primary.size(), rays.shadow.size(), rays.incoherent.size()));

    for (int threads : plan.threadCounts) {
        for (nlohmann::json& row :
             measureRounds(scene, rays, env, plan.contest, plan.kinds, threads, options.builds, options.passes)) {
            const std::string reference = yardstickOf(row);
            const nlohmann::json& ratio = ratiosTo(row, reference)["primary"];
            if (Progress::defaultStyle() != Progress::Style::Quiet)  // a progress line: --quiet drops it
                fmt::print(stderr, "  {} threads={} {} {}: build {:.1f} ms, primary {:.3f} us/query ({:.2f}x {})\n",
                           scene.name, threads, row["accel"].get<std::string>(), row["queries"].get<std::string>(),
                           row["build_ms"].get<double>(), row["primary"]["t_r_us"].get<double>(),
                           ratio.is_null() ? 0.0 : ratio.get<double>(), reference);
            rows.push_back(std::move(row));
        }
    }
    return rows;
}

// What a scene's result key holds of the bench's own settings (bench_resume.h).
nlohmann::json benchMeasurement(const BenchOptions& options, const BenchPlan& plan) {
    nlohmann::json measurement = {{"command", "bench"},
                                  {"builds", options.builds},
                                  {"passes", options.passes},
                                  {"threads", plan.threadCounts},
                                  {"queries", nlohmann::json::array()}};
    for (QueryKind kind : plan.kinds) measurement["queries"].push_back(toString(kind));
    return measurement;
}

// Measures the scenes into `results`, each in a process of its own, and writes them to `out`
// after each scene; a scene --out holds with its result key is kept instead. Returns how many
// scenes failed.
size_t measureScenes(const BenchOptions& options, const BenchPlan& plan, nlohmann::json& results,
                     const std::filesystem::path& out) {
    const std::vector<SceneArgument>& scenes = plan.scenes;
    // Each scene's result key first (bench_resume.h): the scenes --out holds with it are kept.
    const nlohmann::json measurement = benchMeasurement(options, plan);
    const EarlierBench earlier(options.fresh ? std::filesystem::path() : out);
    std::vector<nlohmann::json> keys;
    std::vector<bool> keep;
    ResumeCount resume;
    for (const SceneArgument& scene : scenes) {
        keys.push_back(benchSceneKey(plan.contestAccels, scene.load(options.env), measurement));
        const StoredResult stored =
            options.fresh ? StoredResult{false, "of --fresh"} : earlier.check(scene.id, keys.back());
        resume.add(stored);
        keep.push_back(stored.keep);
    }
    fmt::print(stderr, "bench: {}\n", resume.summary("scenes", "measure"));

    size_t failed = 0;
    for (size_t s = 0; s < scenes.size(); ++s) {
        if (keep[s]) {
            results["scenes"].push_back(earlier.scene(scenes[s].id));
            for (nlohmann::json& row : earlier.rows(scenes[s].id)) results["rows"].push_back(std::move(row));
            continue;
        }
        const JobOutcome outcome = runJobInChild(std::to_string(s), options.jobTimeout);
        if (outcome.passed()) {
            for (nlohmann::json row : outcome.result) {
                row["scene_id"] = scenes[s].id;
                // What ran: the structure with its own settings and plugin (none for Embree's own
                // APIs and the nothing rows, which are no structure of --accel).
                row["structure"] = keys[s]["structures"].value(row["accel"].get<std::string>(), nlohmann::json());
                results["rows"].push_back(std::move(row));
            }
            const std::string name =
                outcome.result.empty() ? scenes[s].id : outcome.result[0]["scene"].get<std::string>();
            results["scenes"].push_back({{"id", scenes[s].id}, {"name", name}, {"result_key", keys[s]}});
        } else {
            ++failed;
            fmt::print(stderr, "[{}/{}] {}: failed: {}\n", s + 1, scenes.size(), scenes[s].id, outcome.failure());
            results["rows"].push_back(
                {{"scene", scenes[s].id}, {"scene_id", scenes[s].id}, {"failed", outcome.failure()}});
        }
        // Written after each scene, so that an interrupted bench keeps the scenes it finished.
        writeFileAtomically(out, results.dump(2) + "\n");
    }
    return failed;
}

// The rows the table shows: those --accel chose with their ISA pairs, with --reference-rows every row.
std::vector<std::string> shownRows(const BenchOptions& options, const BenchPlan& plan, const nlohmann::json& results) {
    std::vector<std::string> shown;
    for (const AccelConfig& config : parseAccelConfigList(options.accels)) {
        shown.push_back(config.label);
        for (const std::string& isa : plan.pairs.isas) shown.push_back(labelAtIsa(config.label, isa));
    }
    if (options.referenceRows)
        for (const nlohmann::json& row : results["rows"])
            if (!row.contains("failed")) shown.push_back(row["accel"].get<std::string>());
    return shown;
}

// The bench the options ask for; returns how many scenes failed.
size_t runBench(BenchOptions& options) {
    const BenchPlan plan = planBench(options);
    if (options.child.isChild()) {
        size_t s = 0;
        if (!parseNumber(options.child.job, s) || s >= plan.scenes.size())
            throw InputError(fmt::format("{} {}: not a scene of this bench", kChildJobOption, options.child.job));
        options.child.run([&] { return measureBenchScene(options, plan, s); });
        return 0;
    }

    const IsaPairs& pairs = plan.pairs;
    nlohmann::json results = {{"provenance", provenanceJson()},
                              {"run", runJson()},
                              {"builds", options.builds},
                              {"passes", options.passes},
                              {"scenes", nlohmann::json::array()},
                              {"rows", nlohmann::json::array()},
                              {"isa_pairs", {{"best", pairs.best}, {"isas", pairs.isas}, {"note", pairs.note}}}};
    const std::filesystem::path out = prepareOutputFile(options.out);
    const size_t failed = measureScenes(options, plan, results, out);
    results["failed_jobs"] = failed;
    writeFileAtomically(out, results.dump(2) + "\n");
    fmt::print("{}", benchTable(results, shownRows(options, plan, results)));
    fmt::print(stderr, "wrote {}\n", out.string());
    if (failed) fmt::print(stderr, "bench: {} of {} scenes failed\n", failed, plan.scenes.size());
    return failed;
}

}  // namespace

void addBenchCommand(CLI::App& app) {
    auto options = std::make_shared<BenchOptions>();
    CLI::App* command = app.add_subcommand("bench", "time builds and queries against Embree (medians, ratios)");
    addBenchOptions(*command, *options);
    command->callback([options] { runJobsGuarded([&] { return runBench(*options); }); });
}

}  // namespace bvhlab
