// `bvhlab tradeoff`: the CSV files and Markdown tables, made from the per-configuration JSON
// files alone (so a resumed run reports everything measured so far).
#include "apps/measure/failed_config.h"
#include "apps/measure/tradeoff.h"
#include "apps/runtime/atomic_write.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/result_key.h"

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

std::string cell(const json& v, const char* format = "{}") {
    if (v.is_null()) return "";
    if (v.is_number_float()) return fmt::format(fmt::runtime(format), v.get<double>());
    if (v.is_number()) return fmt::format("{}", v.get<long long>());
    if (v.is_string()) return v.get<std::string>();
    return v.dump();
}

std::string shown(const json& v, const char* format) { return v.is_null() ? "n/a" : cell(v, format); }

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

// A Markdown table of `rows` under `headers` (with their alignments, "---" or "---:"), without the
// columns that are n/a in every row: a run without sweepbvh has no gap, one without sahbvh no
// build ratio, and a column of n/a would only push the measured ones apart.
std::string markdownTable(const std::vector<std::string>& headers, const std::vector<std::string>& alignments,
                          const std::vector<std::vector<std::string>>& rows) {
    std::vector<size_t> kept;
    for (size_t c = 0; c < headers.size(); ++c)
        if (rows.empty() || std::any_of(rows.begin(), rows.end(), [&](const auto& row) { return row[c] != "n/a"; }))
            kept.push_back(c);
    auto line = [&](const std::vector<std::string>& cells) {
        std::string text = "|";
        for (size_t c : kept) text += " " + cells[c] + " |";
        return text + "\n";
    };
    std::string table = line(headers) + "|";
    for (size_t c : kept) table += alignments[c] + "|";
    table += "\n";
    for (const std::vector<std::string>& row : rows) table += line(row);
    return table;
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
    // scene -> config label -> row
    std::map<std::string, std::map<std::string, Row>> rows;
    std::map<std::string, std::map<std::string, json>> failures;  // scene -> config label -> its failure
    for (const std::string& scene : sceneIds)
        for (const AccelConfig& config : configs) {
            const std::filesystem::path file = dir / scene / (labelAsFileName(config.label) + ".json");
            if (!std::filesystem::exists(file)) continue;
            std::ifstream in(file);
            json stored = json::parse(in);
            if (isFailedConfig(stored)) failures[scene][config.label] = std::move(stored);
            else rows[scene][config.label].stored = std::move(stored);
        }
    for (auto& [scene, byConfig] : rows) {
        const json sweep = byConfig.count("sweepbvh") ? byConfig["sweepbvh"].at("sah") : json();
        for (auto& [label, row] : byConfig) {
            const json r = ratio(row.at("sah"), sweep);
            row.gap = r.is_null() ? json() : json(r.get<double>() - 1.0);
        }
    }

    const std::vector<int> spps = settings.sppSeries();
    const int maxSpp = spps.back();

    // tradeoff.csv
    std::string csv =
        "scene,config,accel,bins,prims,builds,build_ms,build_cpu_ms,sah,sah_gap,nodes,leaves,primary_rays,"
        "t_r_primary_us,t_r_primary_cpu_us,n_it_primary,n_tr_primary,shadow_rays,t_r_shadow_us,t_r_shadow_cpu_us,"
        "n_it_shadow,n_tr_shadow,series_width,series_height,max_spp,render_1spp_ms,render_max_ms,render_1spp_cpu_ms,"
        "render_max_cpu_ms,time_to_image_1spp_ms,time_to_image_max_ms,time_to_image_1spp_cpu_ms,"
        "time_to_image_max_cpu_ms,mismatches_primary,mismatches_shadow,pixels_differing_1spp,failed\n";
    const std::string csvHeader = csv;
    for (const std::string& scene : sceneIds)
        for (const AccelConfig& config : configs) {
            if (failures[scene].count(config.label)) {
                csv += failedConfigCsvRow(failures[scene][config.label], csvHeader);
                continue;
            }
            if (!rows[scene].count(config.label)) continue;
            const Row& r = rows[scene][config.label];
            const json& p = r.stored["primary"];
            const json& s = r.stored["shadow"];
            const std::vector<std::string> cells = {
                scene, config.label, cell(r.at("accel")), cell(r.at("bins")), cell(r.at("prims")),
                std::to_string(r.stored["build_ms_all"].size()), cell(r.at("build_ms"), "{:.3f}"),
                cell(r.at("build_cpu_ms"), "{:.3f}"), cell(r.at("sah"), "{:.6f}"), cell(r.gap, "{:.6f}"),
                cell(r.at("nodes")), cell(r.at("leaves")), cell(p["rays"]), cell(p["t_r_us"], "{:.4f}"),
                cell(p["t_r_cpu_us"], "{:.4f}"), cell(p["n_it"], "{:.3f}"), cell(p["n_tr"], "{:.3f}"), cell(s["rays"]),
                cell(s["t_r_us"], "{:.4f}"), cell(s["t_r_cpu_us"], "{:.4f}"), cell(s["n_it"], "{:.3f}"),
                cell(s["n_tr"], "{:.3f}"), cell(r.at("series_width")), cell(r.at("series_height")),
                std::to_string(maxSpp), cell(r.series(0, "render_ms"), "{:.3f}"), cell(r.lastSeries("render_ms"), "{:.3f}"),
                cell(r.series(0, "render_cpu_ms"), "{:.3f}"), cell(r.lastSeries("render_cpu_ms"), "{:.3f}"),
                cell(r.series(0, "time_to_image_ms"), "{:.3f}"), cell(r.lastSeries("time_to_image_ms"), "{:.3f}"),
                cell(r.series(0, "time_to_image_cpu_ms"), "{:.3f}"), cell(r.lastSeries("time_to_image_cpu_ms"), "{:.3f}"),
                cell(p["mismatches"]), cell(s["mismatches"]),
                cell(r.stored["same_image_1spp"].value("pixels_differing", json())), ""};
            for (size_t i = 0; i < cells.size(); ++i) csv += (i ? "," : "") + cells[i];
            csv += '\n';
        }
    writeFileAtomically(dir / "tradeoff.csv", csv);

    // image_error.csv: the error is the scene's (every structure makes the same image; the
    // spread over structures shows how far that holds), the render time each structure's.
    std::string errors = "scene,spp,rmse,psnr,rmse_spread";
    for (const AccelConfig& config : configs) errors += ",render_ms_" + config.label;
    for (const AccelConfig& config : configs) errors += ",render_cpu_ms_" + config.label;
    errors += "\n";
    for (const std::string& scene : sceneIds) {
        if (rows[scene].empty()) continue;
        const Row& ref = rows[scene].count("embree") ? rows[scene]["embree"] : rows[scene].begin()->second;
        for (size_t i = 0; i < spps.size(); ++i) {
            double lo = INFINITY, hi = -INFINITY;
            for (const auto& [label, row] : rows[scene])
                if (row.series(i, "rmse").is_number()) {
                    lo = std::min(lo, row.series(i, "rmse").get<double>());
                    hi = std::max(hi, row.series(i, "rmse").get<double>());
                }
            errors += fmt::format("{},{},{},{},{}", scene, spps[i], cell(ref.series(i, "rmse"), "{:.7f}"),
                                  cell(ref.series(i, "psnr"), "{:.4f}"), hi >= lo ? fmt::format("{:.3g}", hi - lo) : "");
            for (const char* key : {"render_ms", "render_cpu_ms"})
                for (const AccelConfig& config : configs) {
                    errors += ',';
                    if (rows[scene].count(config.label)) errors += cell(rows[scene][config.label].series(i, key), "{:.3f}");
                }
            errors += "\n";
        }
    }
    writeFileAtomically(dir / "image_error.csv", errors);

    // tradeoff.md: per scene, the summary over scenes, the image error.
    const int w = rows.empty() || rows.begin()->second.empty() ? settings.seriesSize
                                                                : rows.begin()->second.begin()->second.at("series_width").get<int>();
    std::string md = fmt::format(
        "Settings: threads {}; builds: median of up to {} (fewer once they took {:.0f} s); T_R: median of {} pass(es) "
        "over the primary and shadow rays of a {} image; images {}x{} at 1..{} spp, reference {} spp (Embree). Times "
        "are CPU time of the process (one thread at work), which leaves out what the shared machine gave to others; "
        "wall times are in tradeoff.csv. Time to image = T_B + render.\n\n",
        settings.threads, settings.builds, settings.buildBudgetMs * 1e-3, settings.passes,
        settings.raySize > 0 ? fmt::format("{}x{}", settings.raySize, settings.raySize) : std::string("scene-sized"), w, w,
        maxSpp, settings.referenceSpp);
    std::vector<std::vector<std::string>> sceneRows;
    for (const std::string& scene : sceneIds)
        for (const AccelConfig& config : configs) {
            if (failures[scene].count(config.label)) {
                sceneRows.push_back(failedConfigCells(failures[scene][config.label], 10, "n/a"));
                continue;
            }
            if (!rows[scene].count(config.label)) continue;
            const Row& r = rows[scene][config.label];
            sceneRows.push_back({scene, config.label, shown(r.at("build_cpu_ms"), "{:.1f}"), shown(r.at("sah"), "{:.2f}"),
                                 r.gap.is_null() ? "n/a" : fmt::format("{:+.2f}", 100.0 * r.gap.get<double>()),
                                 shown(r.stored["primary"]["t_r_cpu_us"], "{:.3f}"),
                                 shown(r.stored["shadow"]["t_r_cpu_us"], "{:.3f}"),
                                 shown(r.series(0, "time_to_image_cpu_ms"), "{:.0f}"),
                                 shown(r.lastSeries("time_to_image_cpu_ms"), "{:.0f}"),
                                 fmt::format("{} / {}", cell(r.stored["primary"]["mismatches"]),
                                             cell(r.stored["shadow"]["mismatches"]))});
        }
    md += markdownTable({"scene", "config", "T_B [ms]", "SAH", "gap [%]", "T_R primary [µs]", "T_R shadow [µs]",
                         "image 1 spp [ms]", fmt::format("image {} spp [ms]", maxSpp), "mismatches primary / shadow"},
                        {"---", "---", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:"}, sceneRows);

    md += structuresMeasured(dir, sceneIds, configs);

    // The summary: gaps averaged; times as geometric means of per-scene ratios.
    std::string k16 = "sahbvh-K16";
    if (std::none_of(configs.begin(), configs.end(), [&](const AccelConfig& c) { return c.label == k16; }))
        for (const AccelConfig& c : configs)
            if (c.name == "sahbvh") { k16 = c.label; break; }
    md += "\nOver the scenes measured (gaps: mean and max; times: geometric mean of the per-scene ratios):\n\n";
    std::vector<std::vector<std::string>> summaryRows;
    for (const AccelConfig& config : configs) {
        std::vector<json> build, trp, trs, img1, imgMax;
        double gapSum = 0.0, gapMax = -INFINITY;
        int gaps = 0, scenes = 0;
        long long mismatches = 0;
        for (const std::string& scene : sceneIds) {
            auto& byConfig = rows[scene];
            if (!byConfig.count(config.label)) continue;
            ++scenes;
            const Row& r = byConfig[config.label];
            if (r.gap.is_number()) gapSum += r.gap.get<double>(), gapMax = std::max(gapMax, r.gap.get<double>()), ++gaps;
            if (byConfig.count(k16)) build.push_back(ratio(r.at("build_cpu_ms"), byConfig[k16].at("build_cpu_ms")));
            if (byConfig.count("sweepbvh")) {
                trp.push_back(ratio(r.stored["primary"]["t_r_cpu_us"], byConfig["sweepbvh"].stored["primary"]["t_r_cpu_us"]));
                trs.push_back(ratio(r.stored["shadow"]["t_r_cpu_us"], byConfig["sweepbvh"].stored["shadow"]["t_r_cpu_us"]));
            }
            if (byConfig.count("embree")) {
                img1.push_back(ratio(r.series(0, "time_to_image_cpu_ms"), byConfig["embree"].series(0, "time_to_image_cpu_ms")));
                imgMax.push_back(ratio(r.lastSeries("time_to_image_cpu_ms"), byConfig["embree"].lastSeries("time_to_image_cpu_ms")));
            }
            mismatches += r.stored["primary"].value("mismatches", 0LL) + r.stored["shadow"].value("mismatches", 0LL);
        }
        if (!scenes) continue;
        summaryRows.push_back({config.label, std::to_string(scenes),
                               gaps ? fmt::format("{:+.2f}", 100.0 * gapSum / gaps) : "n/a",
                               gaps ? fmt::format("{:+.2f}", 100.0 * gapMax) : "n/a", shown(geoMean(build), "{:.2f}"),
                               shown(geoMean(trp), "{:.2f}"), shown(geoMean(trs), "{:.2f}"), shown(geoMean(img1), "{:.2f}"),
                               shown(geoMean(imgMax), "{:.2f}"), std::to_string(mismatches)});
    }
    md += markdownTable({"config", "scenes", "gap mean [%]", "gap max [%]", fmt::format("T_B / T_B({})", k16),
                         "T_R primary / sweepbvh", "T_R shadow / sweepbvh", "image 1 spp / embree",
                         fmt::format("image {} spp / embree", maxSpp), "mismatches"},
                        {"---", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:"}, summaryRows);

    md += "\nImage error against the reference: PSNR [dB] per samples per pixel (the same for every structure; "
          "largest RMSE spread over structures in the last column)\n\n| scene |";
    for (int spp : spps) md += fmt::format(" {} |", spp);
    md += " spread |\n|---|";
    for (size_t i = 0; i <= spps.size(); ++i) md += "---:|";
    md += "\n";
    for (const std::string& scene : sceneIds) {
        if (rows[scene].empty()) continue;
        const Row& ref = rows[scene].count("embree") ? rows[scene]["embree"] : rows[scene].begin()->second;
        double spread = 0.0;
        md += fmt::format("| {} |", scene);
        for (size_t i = 0; i < spps.size(); ++i) {
            md += fmt::format(" {} |", shown(ref.series(i, "psnr"), "{:.1f}"));
            double lo = INFINITY, hi = -INFINITY;
            for (const auto& [label, row] : rows[scene])
                if (row.series(i, "rmse").is_number()) {
                    lo = std::min(lo, row.series(i, "rmse").get<double>());
                    hi = std::max(hi, row.series(i, "rmse").get<double>());
                }
            if (hi >= lo) spread = std::max(spread, hi - lo);
        }
        md += fmt::format(" {:.1e} |\n", spread);
    }
    writeFileAtomically(dir / "tradeoff.md", md);
    return md;
}

}  // namespace bvhlab
