// `bvhlab tradeoff --builders`: builders.csv, builders_summary.csv and builders.md, made from the
// per-configuration JSON files alone (so a resumed run reports everything measured so far).
#include "apps/measure/builders.h"
#include "apps/measure/failed_config.h"
#include "apps/measure/measured_configs.h"
#include "apps/measure/rank_statistics.h"
#include "apps/runtime/atomic_write.h"
#include "apps/runtime/table_text.h"

#include <fmt/core.h>

#include <cmath>
#include <map>

namespace bvhlab {
namespace {

using nlohmann::json;

constexpr size_t kSets = std::size(kBuilderRaySets);

// T_B is wall time around build() (timedBuild; build_cpu_ms beside it), as the tables of
// docs/builders.md, "Studies", were made. T_R at one thread is the process's CPU time (what a shared
// machine gave to others is left out); with more, wall time (CPU time would add the threads up).
struct TimeKeys {
    const char* build = "build_ms";
    const char* trace;
    explicit TimeKeys(int threads) : trace(threads == 1 ? "t_r_cpu_us" : "t_r_us") {}
};

double geoMean(const std::vector<double>& values) {
    double logSum = 0.0;
    int n = 0;
    for (double v : values)
        if (std::isfinite(v) && v > 0) logSum += std::log(v), ++n;
    return n ? std::exp(logSum / n) : NAN;
}

// One configuration on one scene, with the figures every table takes from it.
struct Row {
    json stored;
    double build = NAN, buildRatio = NAN;  // T_B, and over the baseline's
    double sah = NAN, epo = NAN;
    double trace[kSets] = {NAN, NAN, NAN};
    double toBaseline[kSets] = {NAN, NAN, NAN}, toHigh[kSets] = {NAN, NAN, NAN}, toBare[kSets] = {NAN, NAN, NAN};
    bool pareto[kSets] = {false, false, false};
};

using RowsByLabel = std::map<std::string, Row>;

using Measured = MeasuredConfigs<Row>;

// The ratios over the scenes: geometric means of the per-scene ratios, with their Pareto front.
struct Summary {
    RowsByLabel means;
    std::map<std::string, int> sceneCount;
};

// The labels on the front of (x, y) over the rows with both.
template <typename X, typename Y>
std::vector<std::string> frontOf(const RowsByLabel& rows, X x, Y y) {
    std::vector<std::string> labels;
    std::vector<double> xs, ys;
    for (const auto& [label, row] : rows)
        if (std::isfinite(x(row)) && std::isfinite(y(row)))
            labels.push_back(label), xs.push_back(x(row)), ys.push_back(y(row));
    std::vector<std::string> front;
    for (size_t i : paretoFront(xs, ys)) front.push_back(labels[i]);
    return front;
}

std::string rho(const std::optional<double>& r) { return r ? fmt::format("{:+.2f}", *r) : "n/a"; }

std::string triple(const double (&v)[kSets], int digits) {
    return fmt::format("{} / {} / {}", fixedCell(v[0], digits), fixedCell(v[1], digits), fixedCell(v[2], digits));
}

// The initials of the ray sets on whose front a row lies ("ps": primary and shadow).
std::string paretoMarks(const bool (&p)[kSets]) {
    std::string m;
    for (size_t s = 0; s < kSets; ++s) m += p[s] ? std::string(1, kBuilderRaySets[s][0]) : "";
    return m;
}

Row rowOf(json stored, const TimeKeys& keys) {
    Row row;
    row.stored = std::move(stored);
    row.build = jsonNumber(row.stored[keys.build]);
    row.sah = jsonNumber(row.stored["sah"]);
    row.epo = jsonNumber(row.stored["epo"]);
    for (size_t s = 0; s < kSets; ++s) row.trace[s] = jsonNumber(row.stored[kBuilderRaySets[s]][keys.trace]);
    return row;
}

// Each row of one scene against the yardsticks of that scene, and the front of T_B against T_R.
void compareWithinScene(RowsByLabel& byLabel, const TimeKeys& keys) {
    const Row* base = byLabel.count(kBuildersBaseline) ? &byLabel[kBuildersBaseline] : nullptr;
    const Row* high = byLabel.count(kBuildersHigh) ? &byLabel[kBuildersHigh] : nullptr;
    for (auto& [label, row] : byLabel) {
        if (base) row.buildRatio = row.build / base->build;
        for (size_t s = 0; s < kSets; ++s) {
            if (base) row.toBaseline[s] = row.trace[s] / base->trace[s];
            if (high) row.toHigh[s] = row.trace[s] / high->trace[s];
            if (base && base->stored.contains("bare"))
                row.toBare[s] = row.trace[s] / jsonNumber(base->stored["bare"][kBuilderRaySets[s]][keys.trace]);
        }
    }
    for (size_t s = 0; s < kSets; ++s)
        for (const std::string& label : frontOf(
                 byLabel, [](const Row& r) { return r.build; }, [s](const Row& r) { return r.trace[s]; }))
            byLabel[label].pareto[s] = true;
}

Summary summarise(const Measured& measured, const std::vector<std::string>& sceneIds,
                  const std::vector<AccelConfig>& configs) {
    Summary summary;
    for (const AccelConfig& config : configs) {
        std::vector<double> build, toBase[kSets], toHigh[kSets], toBare[kSets];
        int& scenes = summary.sceneCount[config.label];
        for (const std::string& scene : sceneIds) {
            const Row* r = measured.row(scene, config.label);
            if (!r) continue;
            ++scenes;
            build.push_back(r->buildRatio);
            for (size_t s = 0; s < kSets; ++s)
                toBase[s].push_back(r->toBaseline[s]), toHigh[s].push_back(r->toHigh[s]),
                    toBare[s].push_back(r->toBare[s]);
        }
        if (!scenes) continue;
        Row& m = summary.means[config.label];
        m.buildRatio = geoMean(build);
        for (size_t s = 0; s < kSets; ++s)
            m.toBaseline[s] = geoMean(toBase[s]), m.toHigh[s] = geoMean(toHigh[s]), m.toBare[s] = geoMean(toBare[s]);
    }
    for (size_t s = 0; s < kSets; ++s)
        for (const std::string& label : frontOf(
                 summary.means, [](const Row& r) { return r.buildRatio; },
                 [s](const Row& r) { return r.toBaseline[s]; }))
            summary.means[label].pareto[s] = true;
    return summary;
}

std::string buildersCsv(const Measured& measured, const std::vector<std::string>& sceneIds,
                        const std::vector<AccelConfig>& configs) {
    std::string csv =
        "scene,config,accel,threads,prims,builds,build_ms,build_cpu_ms,build_ratio_embree_medium,sah,epo,"
        "nodes,leaves,avg_leaf,max_leaf";
    for (const char* set : kBuilderRaySets)
        csv += fmt::format(
            ",{0}_rays,t_r_{0}_us,t_r_{0}_cpu_us,n_it_{0},n_tr_{0},ratio_embree_medium_{0},"
            "ratio_embree_high_{0},ratio_embree_bare_{0},pareto_{0}",
            set);
    csv += ",failed\n";
    const std::string csvHeader = csv;
    auto cell = [](const json& v, int digits) {
        return v.is_number_float() ? fixedCell(v.get<double>(), digits)
               : v.is_number()     ? std::to_string(v.get<long long>())
                                   : "";
    };
    for (const std::string& scene : sceneIds)
        for (const AccelConfig& config : configs) {
            if (const json* failure = measured.failure(scene, config.label)) {
                csv += failedConfigCsvRow(*failure, csvHeader);
                continue;
            }
            const Row* row = measured.row(scene, config.label);
            if (!row) continue;
            const Row& r = *row;
            const json& j = r.stored;
            csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}", scene, config.label,
                               j["accel"].get<std::string>(), cell(j["threads"], 0), cell(j["prims"], 0),
                               j["build_ms_all"].size(), cell(j["build_ms"], 3), cell(j["build_cpu_ms"], 3),
                               fixedCell(r.buildRatio, 4), cell(j["sah"], 6), cell(j["epo"], 6), cell(j["nodes"], 0),
                               cell(j["leaves"], 0), cell(j["avg_leaf"], 3), cell(j["max_leaf"], 0));
            for (size_t s = 0; s < kSets; ++s) {
                const json& t = j[kBuilderRaySets[s]];
                csv += fmt::format(",{},{},{},{},{},{},{},{},{}", cell(t["rays"], 0), cell(t["t_r_us"], 5),
                                   cell(t["t_r_cpu_us"], 5), cell(t["n_it"], 3), cell(t["n_tr"], 3),
                                   fixedCell(r.toBaseline[s], 4), fixedCell(r.toHigh[s], 4), fixedCell(r.toBare[s], 4),
                                   r.pareto[s] ? 1 : 0);
            }
            csv += ",\n";  // not failed
        }
    return csv;
}

std::string summaryCsv(const Summary& summary, const std::vector<AccelConfig>& configs) {
    std::string csv = "config,scenes,build_ratio_embree_medium";
    for (const char* set : kBuilderRaySets)
        csv += fmt::format(",ratio_embree_medium_{0},ratio_embree_high_{0},ratio_embree_bare_{0},pareto_{0}", set);
    csv += "\n";
    for (const AccelConfig& config : configs) {
        if (!summary.means.count(config.label)) continue;
        const Row& m = summary.means.at(config.label);
        csv += fmt::format("{},{},{}", config.label, summary.sceneCount.at(config.label), fixedCell(m.buildRatio, 4));
        for (size_t s = 0; s < kSets; ++s)
            csv += fmt::format(",{},{},{},{}", fixedCell(m.toBaseline[s], 4), fixedCell(m.toHigh[s], 4),
                               fixedCell(m.toBare[s], 4), m.pareto[s] ? 1 : 0);
        csv += "\n";
    }
    return csv;
}

// builders.md's first paragraph: what was measured, and how.
std::string settingsParagraph(const TradeoffSettings& settings) {
    return fmt::format(
        "Settings: threads {}; T_B median of up to {} builds (fewer once they took {:.0f} s); T_R median of {} "
        "pass(es) "
        "over the primary, shadow and incoherent rays of a {} image; T_B is wall time (the structure's own timer, "
        "which leaves out the statistics and EPO computed after a build), T_R {}. Ratios (p / s / i: primary / "
        "shadow / incoherent) are T_R over {}'s, {}'s and the bare Embree loop's on {}'s tree (the bench's "
        "embree-bare). Pareto: "
        "the ray sets on whose front of T_B against T_R the configuration lies.\n\n",
        settings.threads, settings.builds, settings.buildBudgetMs * 1e-3, settings.passes,
        settings.raySize > 0 ? fmt::format("{}x{}", settings.raySize, settings.raySize) : std::string("scene-sized"),
        settings.threads == 1 ? "CPU time of the process" : "wall time", kBuildersBaseline, kBuildersHigh,
        kBuildersBaseline);
}

std::string sceneTable(const Measured& measured, const std::vector<std::string>& sceneIds,
                       const std::vector<AccelConfig>& configs) {
    std::string md =
        "| scene | config | T_B [ms] | T_B / medium | SAH | EPO | leaves | T_R p / s / i [µs] | / medium | / high | / "
        "bare "
        "| Pareto |\n|---|---|---:|---:|---:|---:|---:|---|---|---|---|---|\n";
    for (const std::string& scene : sceneIds)
        for (const AccelConfig& config : configs) {
            if (const json* failure = measured.failure(scene, config.label)) {
                md += failedConfigMarkdownRow(*failure, 12);
                continue;
            }
            const Row* row = measured.row(scene, config.label);
            if (!row) continue;
            const Row& r = *row;
            md +=
                fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", scene, config.label,
                            fixedCell(r.build, 1), fixedCell(r.buildRatio, 2), fixedCell(r.sah, 2), fixedCell(r.epo, 3),
                            r.stored["leaves"].is_number() ? std::to_string(r.stored["leaves"].get<long long>()) : "",
                            triple(r.trace, 3), triple(r.toBaseline, 2), triple(r.toHigh, 2), triple(r.toBare, 2),
                            paretoMarks(r.pareto));
        }
    return md;
}

std::string summaryTable(const Summary& summary, const std::vector<AccelConfig>& configs) {
    std::string md =
        "\nOver the scenes measured (geometric means of the per-scene ratios; Pareto over these means):\n\n"
        "| config | scenes | T_B / medium | T_R / medium p / s / i | T_R / high | T_R / bare | Pareto |\n"
        "|---|---:|---:|---|---|---|---|\n";
    for (const AccelConfig& config : configs) {
        if (!summary.means.count(config.label)) continue;
        const Row& m = summary.means.at(config.label);
        md += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", config.label, summary.sceneCount.at(config.label),
                          fixedCell(m.buildRatio, 2), triple(m.toBaseline, 2), triple(m.toHigh, 2), triple(m.toBare, 2),
                          paretoMarks(m.pareto));
    }
    return md;
}

// The trace bar sbvh8 is held to: Embree HIGH, scene by scene.
std::string sbvh8AgainstHigh(const Measured& measured, const std::vector<std::string>& sceneIds) {
    std::string md = "\nsbvh8 faster than embree-high (scenes won / scenes with both):";
    for (size_t s = 0; s < kSets; ++s) {
        int won = 0, both = 0;
        for (const std::string& scene : sceneIds) {
            const Row* sbvh8 = measured.row(scene, "sbvh8");
            const Row* high = measured.row(scene, kBuildersHigh);
            if (!sbvh8 || !high) continue;
            ++both;
            won += sbvh8->trace[s] < high->trace[s];
        }
        md += fmt::format(" {} {}/{}{}", kBuilderRaySets[s], won, both, s + 1 < kSets ? "," : "\n");
    }
    return md;
}

// How well the tree metrics order our builders as T_R does (Embree's trees are invisible),
// within one layout: the 8-wide traversal is faster at a higher SAH (leaves charged by blocks
// of eight), so across layouts the metric would rank the layout, not the tree.
// SAH+EPO is (1 - a) SAH/SAH~ + a EPO/EPO~ with ~ the scene's geometric mean over the group:
// a = 0.5 stated, and the a in 0, 0.05, ..., 1 that ranks best over the pooled scenes (fitted
// on the same data, so an upper bound of what the combination can do here).
struct Layout {
    const char* name;
    bool wide;
};
constexpr Layout kLayouts[] = {{"binary", false}, {"8-wide", true}};

// The tree metrics and T_R of the builders of one layout, each over its geometric mean.
struct NormalisedMetrics {
    std::vector<double> sah, epo, trace[kSets];
};

NormalisedMetrics normalised(const RowsByLabel& byLabel, bool wide) {
    std::vector<double> s0, e0, t0[kSets];
    for (const auto& [label, r] : byLabel)
        if (r.stored.at("accel").get<std::string>().ends_with('8') == wide && std::isfinite(r.sah) &&
            std::isfinite(r.epo) && r.epo > 0) {
            s0.push_back(r.sah), e0.push_back(r.epo);
            for (size_t s = 0; s < kSets; ++s) t0[s].push_back(r.trace[s]);
        }
    NormalisedMetrics metrics;
    const double gs = geoMean(s0), ge = geoMean(e0);
    for (size_t i = 0; i < s0.size(); ++i) metrics.sah.push_back(s0[i] / gs), metrics.epo.push_back(e0[i] / ge);
    for (size_t s = 0; s < kSets; ++s) {
        const double gt = geoMean(t0[s]);
        for (double t : t0[s]) metrics.trace[s].push_back(t / gt);
    }
    return metrics;
}

std::vector<double> combine(const std::vector<double>& sah, const std::vector<double>& epo, double a) {
    std::vector<double> c(sah.size());
    for (size_t i = 0; i < c.size(); ++i) c[i] = (1.0 - a) * sah[i] + a * epo[i];
    return c;
}

// The per-scene table; `pools` gathers each layout's metrics over the scenes.
std::string rankCorrelationPerScene(const Measured& measured, const std::vector<std::string>& sceneIds,
                                    NormalisedMetrics (&pools)[std::size(kLayouts)]) {
    std::string md =
        "\nSpearman's rank correlation of the tree metric with T_R over our builders of one layout (those with SAH "
        "and EPO), per scene (p / s / i):\n\n| scene | layout | builders | SAH | SAH+EPO (a = 0.5) | EPO |\n"
        "|---|---|---:|---|---|---|\n";
    const RowsByLabel none;
    for (const std::string& scene : sceneIds)
        for (size_t g = 0; g < std::size(kLayouts); ++g) {
            const auto byLabel = measured.rows.find(scene);
            const NormalisedMetrics m =
                normalised(byLabel == measured.rows.end() ? none : byLabel->second, kLayouts[g].wide);
            if (m.sah.size() < 2) continue;
            const std::vector<double> both = combine(m.sah, m.epo, 0.5);
            std::string cells[3];
            for (size_t s = 0; s < kSets; ++s) {
                const char* sep = s ? " / " : "";
                cells[0] += sep + rho(spearman(m.sah, m.trace[s]));
                cells[1] += sep + rho(spearman(both, m.trace[s]));
                cells[2] += sep + rho(spearman(m.epo, m.trace[s]));
            }
            md += fmt::format("| {} | {} | {} | {} | {} | {} |\n", scene, kLayouts[g].name, m.sah.size(), cells[0],
                              cells[1], cells[2]);
            NormalisedMetrics& pool = pools[g];
            pool.sah.insert(pool.sah.end(), m.sah.begin(), m.sah.end());
            pool.epo.insert(pool.epo.end(), m.epo.begin(), m.epo.end());
            for (size_t s = 0; s < kSets; ++s)
                pool.trace[s].insert(pool.trace[s].end(), m.trace[s].begin(), m.trace[s].end());
        }
    return md;
}

std::string rankCorrelationPooled(const NormalisedMetrics (&pools)[std::size(kLayouts)]) {
    std::string md =
        "\nPooled over the scenes (each value over its scene's geometric mean in its layout):\n\n"
        "| layout | pairs | ray set | SAH | SAH+EPO (a = 0.5) | SAH+EPO, fitted a | EPO "
        "|\n|---|---:|---|---|---|---|---|\n";
    for (size_t g = 0; g < std::size(kLayouts); ++g) {
        const NormalisedMetrics& pool = pools[g];
        for (size_t s = 0; s < kSets; ++s) {
            double bestA = 0.0;
            std::optional<double> best;
            for (int step = 0; step <= 20; ++step) {
                const double a = 0.05 * step;
                const std::optional<double> r = spearman(combine(pool.sah, pool.epo, a), pool.trace[s]);
                if (r && (!best || *r > *best)) best = r, bestA = a;
            }
            md += fmt::format("| {} | {} | {} | {} | {} | {} (a = {:.2f}) | {} |\n", kLayouts[g].name, pool.sah.size(),
                              kBuilderRaySets[s], rho(spearman(pool.sah, pool.trace[s])),
                              rho(spearman(combine(pool.sah, pool.epo, 0.5), pool.trace[s])), rho(best), bestA,
                              rho(spearman(pool.epo, pool.trace[s])));
        }
    }
    return md;
}

}  // namespace

std::string writeBuildersReport(const std::filesystem::path& dir, const std::vector<std::string>& sceneIds,
                                const std::vector<AccelConfig>& configs, const TradeoffSettings& settings) {
    const TimeKeys keys(settings.threads);
    Measured measured =
        readMeasuredConfigs<Row>(dir, sceneIds, configs, [&](json stored) { return rowOf(std::move(stored), keys); });
    for (auto& [scene, byLabel] : measured.rows) compareWithinScene(byLabel, keys);
    const Summary summary = summarise(measured, sceneIds, configs);
    writeFileAtomically(dir / "builders.csv", buildersCsv(measured, sceneIds, configs));
    writeFileAtomically(dir / "builders_summary.csv", summaryCsv(summary, configs));

    NormalisedMetrics pools[std::size(kLayouts)];
    std::string md = settingsParagraph(settings) + sceneTable(measured, sceneIds, configs) +
                     structuresMeasured(dir, sceneIds, configs) + summaryTable(summary, configs) +
                     sbvh8AgainstHigh(measured, sceneIds);
    md += rankCorrelationPerScene(measured, sceneIds, pools);  // fills the pools first
    md += rankCorrelationPooled(pools);
    writeFileAtomically(dir / "builders.md", md);
    return md;
}

}  // namespace bvhlab
