// `bvhlab tradeoff`: the CSV files and Markdown tables, made from the per-configuration JSON
// files alone (so a resumed run reports everything measured so far).
#include "apps/measure/failed_config.h"
#include "apps/measure/measured_configs.h"
#include "apps/measure/tradeoff.h"
#include "apps/runtime/atomic_write.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/result_key.h"
#include "apps/runtime/table_text.h"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>

namespace bvhlab {
namespace {

using nlohmann::json;

std::string shown(const json& v, const char* format) { return v.is_null() ? "n/a" : jsonCell(v, format); }

json ratio(const json& a, const json& b) {
    return a.is_number() && b.is_number() && b.get<double>() > 0 ? json(a.get<double>() / b.get<double>()) : json();
}

// Geometric mean of the non-null values.
json geoMean(const std::vector<json>& values) {
    double logSum = 0.0;
    int n = 0;
    for (const json& v : values)
        if (v.is_number() && v.get<double>() > 0) logSum += std::log(v.get<double>()), ++n;
    return n ? json(std::exp(logSum / n)) : json();
}

// One row of tradeoff.csv: the stored JSON flattened, with the gap to sweepbvh.
struct Row {
    json stored;
    json gap;  // sah / sah(sweepbvh) - 1
    json at(const std::string& key) const { return stored.value(key, json()); }
    json series(size_t i, const char* key) const {
        const json& s = stored["series"];
        return i < s.size() ? s[i].value(key, json()) : json();
    }
    json lastSeries(const char* key) const {
        const json& s = stored["series"];
        return s.empty() ? json() : s.back().value(key, json());
    }
};

using Measured = MeasuredConfigs<Row>;

// Each configuration's SAH against sweepbvh's on the same scene.
void addGapsToSweep(Measured& measured) {
    for (auto& [scene, byConfig] : measured.rows) {
        const json sweep = byConfig.count("sweepbvh") ? byConfig["sweepbvh"].at("sah") : json();
        for (auto& [label, row] : byConfig) {
            const json r = ratio(row.at("sah"), sweep);
            row.gap = r.is_null() ? json() : json(r.get<double>() - 1.0);
        }
    }
}

// The row whose image error stands for the scene's: Embree's, or the first measured.
const Row& referenceRow(const std::map<std::string, Row>& byConfig) {
    const auto embree = byConfig.find("embree");
    return embree != byConfig.end() ? embree->second : byConfig.begin()->second;
}

// The spread of the RMSE over the structures of one scene at the i-th sample count, if any has one.
std::optional<double> rmseSpread(const std::map<std::string, Row>& byConfig, size_t i) {
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& [label, row] : byConfig)
        if (row.series(i, "rmse").is_number()) {
            lo = std::min(lo, row.series(i, "rmse").get<double>());
            hi = std::max(hi, row.series(i, "rmse").get<double>());
        }
    return hi >= lo ? std::optional<double>(hi - lo) : std::nullopt;
}

std::vector<std::string> tradeoffCsvCells(const std::string& scene, const std::string& label, const Row& r,
                                          int maxSpp) {
    const json& p = r.stored["primary"];
    const json& s = r.stored["shadow"];
    return {scene,
            label,
            jsonCell(r.at("accel")),
            jsonCell(r.at("bins")),
            jsonCell(r.at("prims")),
            std::to_string(r.stored["build_ms_all"].size()),
            jsonCell(r.at("build_ms"), "{:.3f}"),
            jsonCell(r.at("build_cpu_ms"), "{:.3f}"),
            jsonCell(r.at("sah"), "{:.6f}"),
            jsonCell(r.gap, "{:.6f}"),
            jsonCell(r.at("nodes")),
            jsonCell(r.at("leaves")),
            jsonCell(p["rays"]),
            jsonCell(p["t_r_us"], "{:.4f}"),
            jsonCell(p["t_r_cpu_us"], "{:.4f}"),
            jsonCell(p["n_it"], "{:.3f}"),
            jsonCell(p["n_tr"], "{:.3f}"),
            jsonCell(s["rays"]),
            jsonCell(s["t_r_us"], "{:.4f}"),
            jsonCell(s["t_r_cpu_us"], "{:.4f}"),
            jsonCell(s["n_it"], "{:.3f}"),
            jsonCell(s["n_tr"], "{:.3f}"),
            jsonCell(r.at("series_width")),
            jsonCell(r.at("series_height")),
            std::to_string(maxSpp),
            jsonCell(r.series(0, "render_ms"), "{:.3f}"),
            jsonCell(r.lastSeries("render_ms"), "{:.3f}"),
            jsonCell(r.series(0, "render_cpu_ms"), "{:.3f}"),
            jsonCell(r.lastSeries("render_cpu_ms"), "{:.3f}"),
            jsonCell(r.series(0, "time_to_image_ms"), "{:.3f}"),
            jsonCell(r.lastSeries("time_to_image_ms"), "{:.3f}"),
            jsonCell(r.series(0, "time_to_image_cpu_ms"), "{:.3f}"),
            jsonCell(r.lastSeries("time_to_image_cpu_ms"), "{:.3f}"),
            jsonCell(p["mismatches"]),
            jsonCell(s["mismatches"]),
            jsonCell(r.stored["same_image_1spp"].value("pixels_differing", json())),
            ""};
}

std::string tradeoffCsv(const Measured& measured, const std::vector<std::string>& sceneIds,
                        const std::vector<AccelConfig>& configs, int maxSpp) {
    std::string csv =
        "scene,config,accel,bins,prims,builds,build_ms,build_cpu_ms,sah,sah_gap,nodes,leaves,primary_rays,"
        "t_r_primary_us,t_r_primary_cpu_us,n_it_primary,n_tr_primary,shadow_rays,t_r_shadow_us,t_r_shadow_cpu_us,"
        "n_it_shadow,n_tr_shadow,series_width,series_height,max_spp,render_1spp_ms,render_max_ms,render_1spp_cpu_ms,"
        "render_max_cpu_ms,time_to_image_1spp_ms,time_to_image_max_ms,time_to_image_1spp_cpu_ms,"
        "time_to_image_max_cpu_ms,mismatches_primary,mismatches_shadow,pixels_differing_1spp,failed\n";
    const std::string csvHeader = csv;
    for (const std::string& scene : sceneIds)
        for (const AccelConfig& config : configs) {
            if (const json* failure = measured.failure(scene, config.label)) {
                csv += failedConfigCsvRow(*failure, csvHeader);
                continue;
            }
            const Row* r = measured.row(scene, config.label);
            if (!r) continue;
            const std::vector<std::string> cells = tradeoffCsvCells(scene, config.label, *r, maxSpp);
            for (size_t i = 0; i < cells.size(); ++i) csv += (i ? "," : "") + cells[i];
            csv += '\n';
        }
    return csv;
}

// image_error.csv: the error is the scene's (every structure makes the same image; the
// spread over structures shows how far that holds), the render time each structure's.
std::string imageErrorCsv(const Measured& measured, const std::vector<std::string>& sceneIds,
                          const std::vector<AccelConfig>& configs, const std::vector<int>& spps) {
    std::string errors = "scene,spp,rmse,psnr,rmse_spread";
    for (const AccelConfig& config : configs) errors += ",render_ms_" + config.label;
    for (const AccelConfig& config : configs) errors += ",render_cpu_ms_" + config.label;
    errors += "\n";
    for (const std::string& scene : sceneIds) {
        const auto byConfig = measured.rows.find(scene);
        if (byConfig == measured.rows.end() || byConfig->second.empty()) continue;
        const Row& ref = referenceRow(byConfig->second);
        for (size_t i = 0; i < spps.size(); ++i) {
            const std::optional<double> spread = rmseSpread(byConfig->second, i);
            errors +=
                fmt::format("{},{},{},{},{}", scene, spps[i], jsonCell(ref.series(i, "rmse"), "{:.7f}"),
                            jsonCell(ref.series(i, "psnr"), "{:.4f}"), spread ? fmt::format("{:.3g}", *spread) : "");
            for (const char* key : {"render_ms", "render_cpu_ms"})
                for (const AccelConfig& config : configs) {
                    errors += ',';
                    if (const Row* r = measured.row(scene, config.label))
                        errors += jsonCell(r->series(i, key), "{:.3f}");
                }
            errors += "\n";
        }
    }
    return errors;
}

// tradeoff.md's first paragraph: what was measured, and how.
std::string settingsParagraph(const Measured& measured, const TradeoffSettings& settings, int maxSpp) {
    const auto& rows = measured.rows;
    const int w = rows.empty() || rows.begin()->second.empty()
                      ? settings.seriesSize
                      : rows.begin()->second.begin()->second.at("series_width").get<int>();
    return fmt::format(
        "Settings: threads {}; builds: median of up to {} (fewer once they took {:.0f} s); T_R: median of {} pass(es) "
        "over the primary and shadow rays of a {} image; images {}x{} at 1..{} spp, reference {} spp (Embree). Times "
        "are CPU time of the process (one thread at work), which leaves out what the shared machine gave to others; "
        "wall times are in tradeoff.csv. Time to image = T_B + render.\n\n",
        settings.threads, settings.builds, settings.buildBudgetMs * 1e-3, settings.passes,
        settings.raySize > 0 ? fmt::format("{}x{}", settings.raySize, settings.raySize) : std::string("scene-sized"), w,
        w, maxSpp, settings.referenceSpp);
}

std::string sceneTable(const Measured& measured, const std::vector<std::string>& sceneIds,
                       const std::vector<AccelConfig>& configs, int maxSpp) {
    std::vector<std::vector<std::string>> sceneRows;
    for (const std::string& scene : sceneIds)
        for (const AccelConfig& config : configs) {
            if (const json* failure = measured.failure(scene, config.label)) {
                sceneRows.push_back(failedConfigCells(*failure, 10, "n/a"));
                continue;
            }
            const Row* row = measured.row(scene, config.label);
            if (!row) continue;
            const Row& r = *row;
            sceneRows.push_back(
                {scene, config.label, shown(r.at("build_cpu_ms"), "{:.1f}"), shown(r.at("sah"), "{:.2f}"),
                 r.gap.is_null() ? "n/a" : fmt::format("{:+.2f}", 100.0 * r.gap.get<double>()),
                 shown(r.stored["primary"]["t_r_cpu_us"], "{:.3f}"), shown(r.stored["shadow"]["t_r_cpu_us"], "{:.3f}"),
                 shown(r.series(0, "time_to_image_cpu_ms"), "{:.0f}"),
                 shown(r.lastSeries("time_to_image_cpu_ms"), "{:.0f}"),
                 fmt::format("{} / {}", jsonCell(r.stored["primary"]["mismatches"]),
                             jsonCell(r.stored["shadow"]["mismatches"]))});
        }
    return markdownTable({"scene", "config", "T_B [ms]", "SAH", "gap [%]", "T_R primary [µs]", "T_R shadow [µs]",
                          "image 1 spp [ms]", fmt::format("image {} spp [ms]", maxSpp), "mismatches primary / shadow"},
                         {"---", "---", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:"}, sceneRows);
}

// The configuration build times are taken against: sahbvh-K16, or the first sahbvh measured.
std::string buildYardstick(const std::vector<AccelConfig>& configs) {
    std::string k16 = "sahbvh-K16";
    if (std::none_of(configs.begin(), configs.end(), [&](const AccelConfig& c) { return c.label == k16; }))
        for (const AccelConfig& c : configs)
            if (c.name == "sahbvh") {
                k16 = c.label;
                break;
            }
    return k16;
}

// One configuration's row of the summary over the scenes, or nothing where no scene has it.
std::optional<std::vector<std::string>> summaryRow(const Measured& measured, const std::vector<std::string>& sceneIds,
                                                   const std::string& label, const std::string& k16) {
    std::vector<json> build, trp, trs, img1, imgMax;
    double gapSum = 0.0, gapMax = -INFINITY;
    int gaps = 0, scenes = 0;
    long long mismatches = 0;
    for (const std::string& scene : sceneIds) {
        const Row* row = measured.row(scene, label);
        if (!row) continue;
        ++scenes;
        const Row& r = *row;
        if (r.gap.is_number()) gapSum += r.gap.get<double>(), gapMax = std::max(gapMax, r.gap.get<double>()), ++gaps;
        if (const Row* k = measured.row(scene, k16))
            build.push_back(ratio(r.at("build_cpu_ms"), k->at("build_cpu_ms")));
        if (const Row* sweep = measured.row(scene, "sweepbvh")) {
            trp.push_back(ratio(r.stored["primary"]["t_r_cpu_us"], sweep->stored["primary"]["t_r_cpu_us"]));
            trs.push_back(ratio(r.stored["shadow"]["t_r_cpu_us"], sweep->stored["shadow"]["t_r_cpu_us"]));
        }
        if (const Row* embree = measured.row(scene, "embree")) {
            img1.push_back(ratio(r.series(0, "time_to_image_cpu_ms"), embree->series(0, "time_to_image_cpu_ms")));
            imgMax.push_back(ratio(r.lastSeries("time_to_image_cpu_ms"), embree->lastSeries("time_to_image_cpu_ms")));
        }
        mismatches += r.stored["primary"].value("mismatches", 0LL) + r.stored["shadow"].value("mismatches", 0LL);
    }
    if (!scenes) return std::nullopt;
    return std::vector<std::string>{label,
                                    std::to_string(scenes),
                                    gaps ? fmt::format("{:+.2f}", 100.0 * gapSum / gaps) : "n/a",
                                    gaps ? fmt::format("{:+.2f}", 100.0 * gapMax) : "n/a",
                                    shown(geoMean(build), "{:.2f}"),
                                    shown(geoMean(trp), "{:.2f}"),
                                    shown(geoMean(trs), "{:.2f}"),
                                    shown(geoMean(img1), "{:.2f}"),
                                    shown(geoMean(imgMax), "{:.2f}"),
                                    std::to_string(mismatches)};
}

// The summary: gaps averaged; times as geometric means of per-scene ratios.
std::string summaryTable(const Measured& measured, const std::vector<std::string>& sceneIds,
                         const std::vector<AccelConfig>& configs, int maxSpp) {
    const std::string k16 = buildYardstick(configs);
    std::vector<std::vector<std::string>> summaryRows;
    for (const AccelConfig& config : configs)
        if (auto row = summaryRow(measured, sceneIds, config.label, k16)) summaryRows.push_back(std::move(*row));
    return "\nOver the scenes measured (gaps: mean and max; times: geometric mean of the per-scene ratios):\n\n" +
           markdownTable({"config", "scenes", "gap mean [%]", "gap max [%]", fmt::format("T_B / T_B({})", k16),
                          "T_R primary / sweepbvh", "T_R shadow / sweepbvh", "image 1 spp / embree",
                          fmt::format("image {} spp / embree", maxSpp), "mismatches"},
                         {"---", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:"}, summaryRows);
}

std::string imageErrorTable(const Measured& measured, const std::vector<std::string>& sceneIds,
                            const std::vector<int>& spps) {
    std::string md =
        "\nImage error against the reference: PSNR [dB] per samples per pixel (the same for every structure; "
        "largest RMSE spread over structures in the last column)\n\n| scene |";
    for (int spp : spps) md += fmt::format(" {} |", spp);
    md += " spread |\n|---|";
    for (size_t i = 0; i <= spps.size(); ++i) md += "---:|";
    md += "\n";
    for (const std::string& scene : sceneIds) {
        const auto byConfig = measured.rows.find(scene);
        if (byConfig == measured.rows.end() || byConfig->second.empty()) continue;
        const Row& ref = referenceRow(byConfig->second);
        double spread = 0.0;
        md += fmt::format("| {} |", scene);
        for (size_t i = 0; i < spps.size(); ++i) {
            md += fmt::format(" {} |", shown(ref.series(i, "psnr"), "{:.1f}"));
            if (const std::optional<double> s = rmseSpread(byConfig->second, i)) spread = std::max(spread, *s);
        }
        md += fmt::format(" {:.1e} |\n", spread);
    }
    return md;
}

}  // namespace

std::string structuresMeasured(const std::filesystem::path& dir, const std::vector<std::string>& sceneIds,
                               const std::vector<AccelConfig>& configs) {
    std::string md = "\nStructures, with their own settings:\n\n";
    for (const AccelConfig& config : configs)
        for (const std::string& scene : sceneIds) {
            const std::filesystem::path file = dir / scene / (config.label + ".json");
            if (!std::filesystem::exists(file)) continue;
            std::ifstream in(file);
            const json key = json::parse(in).value("result_key", json::object());
            md += fmt::format("- `{}`: {}\n", config.label,
                              key.contains("structure") ? describeStructure(key["structure"]) : "not recorded");
            break;
        }
    return md;
}

std::string writeTradeoffReport(const std::filesystem::path& dir, const std::vector<std::string>& sceneIds,
                                const std::vector<AccelConfig>& configs, const TradeoffSettings& settings) {
    Measured measured = readMeasuredConfigs<Row>(dir, sceneIds, configs, [](json stored) {
        return Row{std::move(stored), json()};
    });
    addGapsToSweep(measured);
    const std::vector<int> spps = settings.sppSeries();
    const int maxSpp = spps.back();
    writeFileAtomically(dir / "tradeoff.csv", tradeoffCsv(measured, sceneIds, configs, maxSpp));
    writeFileAtomically(dir / "image_error.csv", imageErrorCsv(measured, sceneIds, configs, spps));

    // tradeoff.md: per scene, the summary over scenes, the image error.
    const std::string md =
        settingsParagraph(measured, settings, maxSpp) + sceneTable(measured, sceneIds, configs, maxSpp) +
        structuresMeasured(dir, sceneIds, configs) + summaryTable(measured, sceneIds, configs, maxSpp) +
        imageErrorTable(measured, sceneIds, spps);
    writeFileAtomically(dir / "tradeoff.md", md);
    return md;
}

}  // namespace bvhlab
