#include "apps/batch/batch_table.h"

#include "apps/animate/animate_report.h"
#include "apps/batch/contact_sheet.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/result_key.h"
#include "apps/runtime/table_text.h"
#include "framework/core/error.h"

#include <bvhlab/counters.h>
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace bvhlab {
namespace {

using nlohmann::json;

// One line of the table: a render of a job, with its build's columns; or a job that failed.
struct Row {
    std::string scene, accel;
    json structure;      // the structure part of the job's result key (result_key.h): what ran
    std::string failed;  // why the job left no results (child_job.h's JobOutcome::failure()); empty if it ran
    bool shadows = false;
    json prims, leaves, nodes, sah, buildMs;  // of the build, shared by both renders
    json trUs, nQ, renderMs;                  // over all queries of this render
    json counters = json::object();           // likewise, the counters of kQueryCounters with a column, by key
};

// T_R and the counters (N_IT, N_TR, ...) averaged over every query of a render, primary and shadow
// together.
json allQueries(const json& run) {
    const json& p = run.at("primary");
    const json& s = run.at("shadow");
    const double qp = p.at("queries").get<double>(), qs = s.at("queries").get<double>(), q = qp + qs;
    // A kind of query that was not traced (no shadow rays) adds no weight; one that was traced
    // but not counted (Embree's N_IT) makes the figure unavailable; nothing traced at all: n/a.
    auto mean = [&](const char* key) -> json {
        double sum = 0.0;
        for (const json* part : {&p, &s}) {
            const double n = part->at("queries").get<double>();
            if (n == 0.0) continue;
            if (part->at(key).is_null()) return nullptr;
            sum += part->at(key).get<double>() * n;
        }
        return q > 0 ? json(sum / q) : json();
    };
    json all = {{"queries", p.at("queries").get<uint64_t>() + s.at("queries").get<uint64_t>()},
                {"t_r_us", mean("t_r_us")}};
    for (const QueryCounter& c : kQueryCounters) all[c.key] = mean(c.key);
    return all;
}

bool jobFailed(const json& job) { return job.contains("failed"); }
// A job of an animated scene (Batch::animate): an animation measured, not two renders.
bool isAnimationJob(const json& job) { return job.value("animated", false); }

Row failedRow(const json& job) {
    Row row;
    row.scene = job.at("scene").get<std::string>();
    row.accel = job.at("accel").get<std::string>();
    row.failed = job.at("failed").get<std::string>();
    return row;
}

Row makeRow(const json& job, bool shadows) {
    const json& run = job.at("runs").at(shadows ? "shadows" : "no_shadows");
    const json all = allQueries(run);
    json counters = json::object();
    for (const QueryCounter& c : kQueryCounters)
        if (c.column) counters[c.key] = all.at(c.key);
    return {job.at("scene").get<std::string>(),
            job.at("accel").get<std::string>(),
            job.value("result_key", json::object()).value("structure", json()),
            "",
            shadows,
            run.at("prims"),
            run.at("leaves"),
            run.at("nodes"),
            run.at("sah"),
            run.at("build_ms"),
            all.at("t_r_us"),
            all.at("queries"),
            run.at("render_ms"),
            std::move(counters)};
}

// A number as the Markdown table shows it; null is "n/a" (unavailable, never 0).
std::string cell(const json& v, const char* format) {
    if (v.is_null()) return "n/a";
    if (v.is_number_integer() || v.is_number_unsigned()) return fmt::format("{}", v.get<uint64_t>());
    return fmt::format(fmt::runtime(format), v.get<double>());
}

// A number as the CSV holds it: shortest exact form, empty when unavailable.
std::string csvCell(const json& v) {
    if (v.is_null()) return "";
    if (v.is_number_integer() || v.is_number_unsigned()) return fmt::format("{}", v.get<uint64_t>());
    return fmt::format("{}", v.get<double>());
}

// Keys that may differ between jobs of one batch: what scene, view, accelerator, output.
bool variesByJob(const std::string& key) {
    for (const char* prefix : {"Scene::", "Camera::", "Lights::", "Output::", "ASDS::", "Batch::"})
        if (key.rfind(prefix, 0) == 0) return true;
    return key == "SetRayTracing::shadows";  // batch renders both
}

// Settings the jobs were run with ("key=value", or "key varies") and warnings where jobs differ.
std::pair<std::vector<std::string>, std::vector<std::string>> settingsOf(const std::vector<json>& jobs) {
    std::vector<std::string> settings, warnings;
    if (jobs.empty()) return {settings, warnings};
    std::map<std::string, std::set<std::string>> values;
    for (const json& job : jobs) {
        if (jobFailed(job)) continue;
        const json env = job.value("env", json::object());  // kept alive for the loop
        for (const auto& [key, v] : env.items())
            if (!variesByJob(key)) values[key].insert(v.value("value", std::string()));
    }
    for (const auto& [key, set] : values)
        if (set.size() > 1)
            warnings.push_back(fmt::format("jobs were run with different {}: {}", key, fmt::join(set, " / ")));
    std::set<std::string> commits, cpus, sizes;
    for (const json& job : jobs) {
        if (jobFailed(job)) continue;
        commits.insert(job.value("provenance", json::object()).value("git_commit", std::string("?")));
        cpus.insert(job.value("provenance", json::object()).value("cpu", std::string("?")));
        const json& image = job.value("image", json::object());
        sizes.insert(fmt::format("{}x{}", image.value("width", 0), image.value("height", 0)));
    }
    if (commits.size() > 1)
        warnings.push_back(fmt::format("jobs come from different commits: {}", fmt::join(commits, ", ")));
    if (cpus.size() > 1)
        warnings.push_back(
            fmt::format("jobs ran on different CPUs (timings not comparable): {}", fmt::join(cpus, "; ")));

    auto show = [&](const std::string& key, const std::string& label) {
        const auto it = values.find(key);
        if (it == values.end()) return;
        settings.push_back(it->second.size() == 1 ? fmt::format("{}={}", label, *it->second.begin())
                                                  : fmt::format("{} varies", label));
    };
    settings.push_back(sizes.size() == 1 ? fmt::format("image {}", *sizes.begin()) : "image size varies");
    show("SetRayTracing::threads", "threads");
    show("SetRayTracing::cntSamples", "samples");
    show("SetRayTracing::depthLimit", "depthLimit");
    return {settings, warnings};
}

// A scene's heat maps share one full scale when its jobs ran together; merged shards may not.
std::vector<std::string> heatmapScaleWarnings(const std::vector<json>& jobs) {
    std::map<std::string, std::set<float>> scales;  // scene -> full scales of its heat maps
    for (const json& job : jobs) {
        if (jobFailed(job) || isAnimationJob(job)) continue;
        for (const auto& [name, run] : job.at("runs").items())
            if (run.contains("heatmap") && run["heatmap"].contains("scale"))
                scales[job.at("scene").get<std::string>()].insert(run["heatmap"]["scale"].get<float>());
    }
    std::vector<std::string> warnings;
    for (const auto& [scene, set] : scales)
        if (set.size() > 1)
            warnings.push_back(
                fmt::format("the heat maps of {} have different full scales ({}): its jobs ran in "
                            "different shards; set Output::heatmapScale for one scale",
                            scene, fmt::join(set, ", ")));
    return warnings;
}

// Whether the structure of a row is a plugin's compiled without optimisation.
bool unoptimised(const json& structure) {
    return structure.is_object() && structure.at("plugin").is_object() &&
           !structure["plugin"].at("optimized").get<bool>();
}

// Each accelerator of the table with its own settings and its plugin, a line each ("- `scan`:
// Scan::passes=1; plugin scan.so, CRC-32 1a2b3c4d"); one per scene where its scenes' differ.
std::vector<std::string> structureLines(const std::vector<json>& jobs) {
    std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::vector<std::string>>>>> byAccel;
    for (const json& job : jobs) {
        const std::string accel = job.at("accel").get<std::string>(), scene = job.at("scene").get<std::string>();
        const json structure = job.value("result_key", json::object()).value("structure", json());
        const std::string text =
            structure.is_null() ? "not recorded (a job of an older bvhlab)" : describeStructure(structure);
        auto it = std::find_if(byAccel.begin(), byAccel.end(), [&](const auto& a) { return a.first == accel; });
        if (it == byAccel.end()) it = byAccel.insert(byAccel.end(), {accel, {}});
        auto same = std::find_if(it->second.begin(), it->second.end(), [&](const auto& d) { return d.first == text; });
        if (same == it->second.end())
            it->second.push_back({text, {scene}});
        else
            same->second.push_back(scene);
    }
    std::vector<std::string> lines;
    for (const auto& [accel, descriptions] : byAccel)
        for (const auto& [text, scenes] : descriptions)
            lines.push_back(descriptions.size() == 1
                                ? fmt::format("- `{}`: {}", accel, text)
                                : fmt::format("- `{}` ({}): {}", accel, fmt::join(scenes, ", "), text));
    return lines;
}

std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Per animated scene, in table order, its jobs as `bvhlab animate`'s results (animate_report.h):
// the scene and frames of its first finished job, a contender per job (a failed one with its reason).
std::vector<json> animationResults(const std::vector<json>& jobs) {
    std::vector<json> animations;
    for (const json& job : jobs) {
        if (!isAnimationJob(job)) continue;
        const std::string scene = job.at("scene").get<std::string>();
        if (animations.empty() || animations.back().at("scene").at("id") != scene)
            animations.push_back({{"scene", {{"id", scene}}}, {"contenders", json::array()}});
        json& animation = animations.back();
        if (jobFailed(job)) {
            const std::string accel = job.at("accel").get<std::string>();
            animation["contenders"].push_back(
                {{"label", accel}, {"accel", accel}, {"failed", job.at("failed")}, {"rows", json::array()}});
            continue;
        }
        if (!animation.contains("frames")) {
            animation.update(job.at("animation"));
            animation["scene"]["id"] = scene;
        }
        animation["contenders"].push_back(job.at("contender"));
    }
    return animations;
}

// An animated scene's section: animate's summary table of its jobs, under what they measured.
std::string animationMarkdown(const json& animation) {
    const json& scene = animation.at("scene");
    std::string md = fmt::format("\n## {}: an animation\n\n", scene.at("id").get<std::string>());
    if (animation.contains("frames")) {
        const std::vector<int> frames = animation.at("frames").get<std::vector<int>>();
        md += fmt::format(
            "{} frames measured of {} ({} to {}), {} triangles; each structure under its Animate::policy, one "
            "trace of each frame's primary and shadow rays per frame; threads: {} (animation_frames.csv has every "
            "frame).\n\n",
            frames.size(), scene.value("frame_count", 0), frames.front(), frames.back(),
            scene.value("triangles", size_t(0)), animation.value("threads", 0));
    }
    return md + animateSummaryTable(animation);
}

// Markdown in the report's layout.
std::string batchMarkdown(const std::vector<json>& jobs, const std::vector<Row>& rows, size_t batchJobs,
                          const std::vector<std::string>& settings, const std::vector<std::string>& warnings,
                          size_t failedJobs) {
    std::set<std::string> scenes, accels;
    size_t fromCache = 0;
    for (const json& job : jobs) {
        scenes.insert(job.at("scene").get<std::string>());
        accels.insert(job.at("accel").get<std::string>());
        fromCache += job.value("scene_from_cache", false);
    }
    std::string md;
    md += fmt::format("# bvhlab batch: {} scenes x {} accelerators, without and with shadows\n\n", scenes.size(),
                      accels.size());
    md += fmt::format("Settings: {}.\n\n", fmt::join(settings, ", "));
    md += fmt::format("Structures, with their own settings:\n{}\n\n", fmt::join(structureLines(jobs), "\n"));
    for (const std::string& w : warnings) md += fmt::format("**Warning:** {}.\n\n", w);
    std::string counterColumns, counterAlignment, counterBlanks;
    for (const QueryCounter& c : kQueryCounters)
        if (c.column)
            counterColumns += fmt::format(" {} |", c.column), counterAlignment += "--:|", counterBlanks += " |";
    md += fmt::format(
        "| scene | accel | | #Prims | #Leaves | #Nodes | SAH | T_B [ms] | T_R [µs] |{} N_Q | render [ms] |\n",
        counterColumns);
    md += fmt::format("|:--|:--|:--|--:|--:|--:|--:|--:|--:|{}--:|--:|\n", counterAlignment);
    for (const Row& r : rows) {
        if (!r.failed.empty()) {
            md += fmt::format("| {} | {} | failed: {} | | | | | | |{} | |\n", r.scene, r.accel, markdownText(r.failed),
                              counterBlanks);
            continue;
        }
        if (!r.shadows)
            md +=
                fmt::format("| {} | {}{} | | {} | {} | {} | {} | {} ", r.scene, r.accel,
                            unoptimised(r.structure) ? " (unoptimised)" : "", cell(r.prims, "{}"), cell(r.leaves, "{}"),
                            cell(r.nodes, "{}"), cell(r.sah, "{:.2f}"), cell(r.buildMs, "{:.1f}"));
        else
            md += "| | | + shadows | | | | | ";
        md += fmt::format("| {} |", cell(r.trUs, "{:.3f}"));
        for (const QueryCounter& c : kQueryCounters)
            if (c.column) md += fmt::format(" {} |", cell(r.counters.at(c.key), "{:.2f}"));
        md += fmt::format(" {} | {} |\n", cell(r.nQ, "{}"), cell(r.renderMs, "{:.1f}"));
    }
    md +=
        "\nT_B: build time. T_R: µs per query (thread time inside the query loops / queries). N_IT, N_TR: "
        "ray-triangle tests and nodes visited per query. N_Q: queries. SAH: normalised by the root box, with "
        "C_trav and C_isect as set. Render time: wall, build excluded. \"+ shadows\": the same build rendered "
        "with a shadow ray per light; T_R, N_IT and N_TR averaged over all its queries (primary and shadow "
        "together), N_Q counting them all (results.json keeps them apart). n/a: not available (Embree shows "
        "no tree and counts nothing). failed: the job crashed, threw or ran out of time (--job-timeout), "
        "and left no results.\n\n";
    md += fmt::format(
        "Jobs: {}{}{} (a still scene's: one build serving both renders; an animated scene's: a build and "
        "an update per frame); the scene came from the scene cache in {} of them.",
        jobs.size(), jobs.size() < batchJobs ? fmt::format(" of the batch's {}", batchJobs) : "",
        failedJobs ? fmt::format(", {} of them failed", failedJobs) : "", fromCache);
    if (!jobs.empty()) {
        const json& p = jobs.front().value("provenance", json::object());
        md += fmt::format(" Commit {}, {}, {}.", p.value("git_commit", std::string("?")),
                          p.value("cpu", std::string("?")), p.value("compiler", std::string("?")));
    }
    md += "\n";
    return md;
}

// CSV: every column on both rows; a failed job's one row has only its reason. The structure's
// own settings as KEY=value;KEY=value, its plugin's file, CRC-32 and whether it was optimised
// (empty for bvhlab's own).
std::string batchCsv(const std::vector<Row>& rows) {
    std::string csv = "scene,accel,shadows,prims,leaves,nodes,sah,t_b_ms,t_r_us,";
    for (const QueryCounter& c : kQueryCounters)
        if (c.column) csv += fmt::format("{},", c.key);
    csv += "n_q,render_ms,settings,plugin,plugin_crc32,plugin_optimized,failed\n";
    for (const Row& r : rows) {
        std::vector<std::string> settings;
        const json plugin = r.structure.is_object() ? r.structure.at("plugin") : json();
        if (r.structure.is_object())
            for (const auto& [key, value] : r.structure.at("keys").items())
                settings.push_back(key + "=" + value.get<std::string>());
        csv += fmt::format("{},{},{},{},{},{},{},{},{},", csvText(r.scene), csvText(r.accel),
                           r.failed.empty() ? (r.shadows ? "true" : "false") : "", csvCell(r.prims), csvCell(r.leaves),
                           csvCell(r.nodes), csvCell(r.sah), csvCell(r.buildMs), csvCell(r.trUs));
        for (const QueryCounter& c : kQueryCounters)
            if (c.column) csv += fmt::format("{},", csvCell(r.counters.value(c.key, json())));
        csv += fmt::format("{},{},{},{},{},{},{}\n", csvCell(r.nQ), csvCell(r.renderMs),
                           csvText(fmt::format("{}", fmt::join(settings, ";"))),
                           plugin.is_null() ? "" : csvText(plugin.at("file").get<std::string>()),
                           plugin.is_null() ? "" : plugin.at("crc32").get<std::string>(),
                           plugin.is_null()                     ? ""
                           : plugin.at("optimized").get<bool>() ? "true"
                                                                : "false",
                           csvText(r.failed));
    }
    return csv;
}

// JSON: the table's rows, and per job primary and shadow queries apart.
json batchJson(const std::vector<json>& jobs, const std::vector<Row>& rows, const std::vector<std::string>& settings,
               const std::vector<std::string>& warnings, size_t failedJobs) {
    json j = {{"format", "bvhlab-batch-results-1"}, {"settings", settings},  {"warnings", warnings},
              {"failed_jobs", failedJobs},          {"rows", json::array()}, {"jobs", json::array()}};
    for (const Row& r : rows) {
        if (!r.failed.empty()) {
            j["rows"].push_back({{"scene", r.scene}, {"accel", r.accel}, {"failed", r.failed}});
            continue;
        }
        json row = {{"scene", r.scene}, {"accel", r.accel},        {"shadows", r.shadows},
                    {"prims", r.prims}, {"leaves", r.leaves},      {"nodes", r.nodes},
                    {"sah", r.sah},     {"t_b_ms", r.buildMs},     {"t_r_us", r.trUs},
                    {"n_q", r.nQ},      {"render_ms", r.renderMs}, {"structure", r.structure}};
        row.update(r.counters);
        j["rows"].push_back(std::move(row));
    }
    for (const json& job : jobs) {
        if (jobFailed(job)) {
            j["jobs"].push_back({{"job", job.at("job")},
                                 {"scene", job.at("scene")},
                                 {"accel", job.at("accel")},
                                 {"failed", job.at("failed")}});
            continue;
        }
        json summary = {{"job", job.at("job")},
                        {"scene", job.at("scene")},
                        {"accel", job.at("accel")},
                        {"scene_file", job.value("scene_file", std::string())},
                        {"scene_from_cache", job.value("scene_from_cache", false)}};
        for (const char* key : {"prims", "degenerate", "leaves", "nodes", "sah", "build_ms", "bytes", "max_depth"})
            summary[key] = job["runs"]["no_shadows"].value(key, json());
        for (const char* name : {"no_shadows", "shadows"}) {
            const json& run = job["runs"][name];
            summary[name] = {{"render_ms", run["render_ms"]},
                             {"primary", run["primary"]},
                             {"shadow", run["shadow"]},
                             {"all", allQueries(run)},
                             {"images", run.value("images", json::object())}};
        }
        j["jobs"].push_back(std::move(summary));
    }
    return j;
}

}  // namespace

std::string batchJobName(const std::string& scene, const std::string& accel) {
    return labelAsFileName(scene) + "__" + labelAsFileName(accel);
}

std::vector<json> readBatchJobs(const std::filesystem::path& dir, const BatchSettings& settings) {
    // Table position of a job of this batch; none for another batch's.
    auto position = [&](const json& job) -> std::optional<std::pair<size_t, size_t>> {
        const BatchSettings::Scene* scene = settings.scene(job.at("scene").get<std::string>());
        const auto accel =
            std::find(settings.accels.begin(), settings.accels.end(), job.at("accel").get<std::string>());
        if (!scene || accel == settings.accels.end() || job.value("settings", std::string()) != scene->hash)
            return std::nullopt;
        return std::pair(size_t(scene - settings.scenes.data()), size_t(accel - settings.accels.begin()));
    };
    std::vector<std::pair<std::pair<size_t, size_t>, json>> jobs;  // with their table positions
    const std::filesystem::path folder = dir / "jobs";
    if (!std::filesystem::is_directory(folder)) return {};
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
        if (entry.path().extension() != ".json") continue;
        try {
            json job = json::parse(readText(entry.path()));
            if (job.value("format", std::string()) != "bvhlab-batch-job-1")
                throw std::runtime_error("not a batch job file");
            if (!jobFailed(job) && isAnimationJob(job))
                (void)job.at("animation").at("scene"), (void)job.at("contender").at("rows");  // what the tables need
            else if (!jobFailed(job))
                makeRow(job, false), makeRow(job, true);
            const auto at = position(job);
            if (!at)
                throw std::runtime_error(
                    "a job of another batch (its scene, accelerator or settings are not this folder's)");
            jobs.emplace_back(*at, std::move(job));
        } catch (const std::exception& e) {
            fmt::print(stderr, "warning: {}: skipped: {}\n", entry.path().string(), e.what());
        }
    }
    std::sort(jobs.begin(), jobs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<json> sorted;
    for (auto& [at, job] : jobs) sorted.push_back(std::move(job));
    return sorted;
}

BatchTables makeBatchTables(const std::vector<json>& jobs, size_t batchJobs) {
    BatchTables t;
    const auto [settings, warnings] = settingsOf(jobs);
    t.warnings = warnings;
    for (const std::string& w : heatmapScaleWarnings(jobs)) t.warnings.push_back(w);

    std::vector<Row> rows;
    std::vector<json> stillJobs;
    for (const json& job : jobs) {
        t.failedJobs += jobFailed(job);
        if (isAnimationJob(job)) continue;
        stillJobs.push_back(job);
        if (jobFailed(job))
            rows.push_back(failedRow(job));
        else
            rows.push_back(makeRow(job, false)), rows.push_back(makeRow(job, true));
    }
    const std::vector<json> animations = animationResults(jobs);

    t.markdown = batchMarkdown(jobs, rows, batchJobs, settings, t.warnings, t.failedJobs);
    for (const json& animation : animations) t.markdown += animationMarkdown(animation);
    t.csv = batchCsv(rows);
    t.json = batchJson(stillJobs, rows, settings, t.warnings, t.failedJobs);
    t.json["animations"] = animations;
    for (const json& animation : animations) {
        const std::string id = animation.at("scene").at("id").get<std::string>();
        // A column naming the scene before animate's own; the header once.
        std::istringstream lines(animateFramesCsv(animation));
        std::string line;
        for (bool header = true; std::getline(lines, line); header = false)
            if (!header || t.framesCsv.empty())
                t.framesCsv += (header ? std::string("scene") : csvText(id)) + "," + line + "\n";
    }
    return t;
}

BatchTables writeBatchResults(const std::filesystem::path& dir) {
    const std::optional<BatchSettings> batch = readBatchSettings(dir);
    if (!batch) throw InputError(fmt::format("{}: no batch.json, so no batch to make tables of", dir.string()));
    const std::vector<json> jobs = readBatchJobs(dir, *batch);
    BatchTables t = makeBatchTables(jobs, batch->jobCount());
    std::ofstream(dir / "results.md") << t.markdown;
    std::ofstream(dir / "results.csv") << t.csv;
    std::ofstream(dir / "results.json") << t.json.dump(2) << "\n";
    if (!t.framesCsv.empty()) std::ofstream(dir / "animation_frames.csv") << t.framesCsv;

    // The contact sheet: a row per scene, per accelerator the render without and with shadows.
    std::vector<std::vector<ContactImage>> sheet;
    std::string previousScene;
    std::vector<std::string> accels;  // in table order
    for (const json& job : jobs) {
        if (isAnimationJob(job)) continue;  // no images
        const std::string scene = job.at("scene").get<std::string>(), accel = job.at("accel").get<std::string>();
        if (std::find(accels.begin(), accels.end(), accel) == accels.end()) accels.push_back(accel);
        if (sheet.empty() || scene != previousScene) sheet.emplace_back();
        previousScene = scene;
        for (const char* name : {"no_shadows", "shadows"}) {
            const std::string png =
                jobFailed(job) ? "" : job["runs"][name].value("images", json::object()).value("png", std::string());
            sheet.back().push_back(
                {png.empty() ? std::filesystem::path() : dir / png,
                 fmt::format("{} {}{}{}", scene, accel, std::string(name) == "shadows" ? " +shadows" : "",
                             jobFailed(job) ? " (failed)" : "")});
        }
    }
    std::vector<std::string> settings;  // the few that fit in the title
    for (const std::string& s : t.json["settings"].get<std::vector<std::string>>())
        for (const char* key : {"image", "threads"})
            if (s.find(key) != std::string::npos) settings.push_back(s);
    writeContactSheet(dir / "contact_sheet.png", sheet,
                      fmt::format("bvhlab batch: {} scenes x {}; {}", sheet.size(), fmt::join(accels, ", "),
                                  fmt::join(settings, ", ")));
    return t;
}

}  // namespace bvhlab
