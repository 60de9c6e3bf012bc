#include "apps/animate/animate_report.h"

#include "apps/runtime/table_text.h"

#include <fmt/core.h>

#include <cmath>
#include <iterator>
#include <vector>

namespace bvhlab {
namespace {

using nlohmann::json;

// A member of a results file's object, null where it is missing (a failed contender's short row).
const json& memberOf(const json& object, const char* key) {
    static const json null;
    const auto it = object.find(key);
    return it != object.end() ? *it : null;
}

constexpr const char* kAnimateRayKinds[] = {"primary", "shadow"};

// A counter per ray (N_IT, N_TR) over the primary and shadow rays of some frames, weighted by
// their rays: NaN once rays that were traced were not counted (Embree's N_IT is null).
struct PerRayCounter {
    double sum = 0.0, rays = 0.0;
    void add(const json& row, const char* key) {
        for (const char* kind : kAnimateRayKinds) {
            const double n = jsonNumber(memberOf(memberOf(row, kind), "rays"));
            if (!(n > 0)) continue;
            sum += jsonNumber(memberOf(memberOf(row, kind), key)) * n;
            rays += n;
        }
    }
    double mean() const { return rays > 0 ? sum / rays : NAN; }
};

// T_R of a frame: its primary and its shadow rays.
double frameTraceMs(const json& row) {
    double ms = 0.0;
    for (const char* kind : kAnimateRayKinds) ms += jsonNumber(memberOf(memberOf(row, kind), "ms"));
    return ms;
}

double frameCostMs(const json& row) { return jsonNumber(memberOf(row, "update_ms")) + frameTraceMs(row); }

bool rowChecked(const json& row) { return memberOf(row, "agreement").is_object(); }

// The SAH of a frame over the contender's first frame's.
double frameSahRatio(const json& row, const json& rows) {
    const double first = rows.empty() ? NAN : jsonNumber(memberOf(rows.front(), "sah"));
    return first > 0 ? jsonNumber(memberOf(row, "sah")) / first : NAN;
}

// A contender's figures over its measured frames.
struct ContenderTotals {
    std::string label, failed, skipped;  // why it failed, or why it could not run its policy
    bool embree = false;
    const json* rows = nullptr;
    size_t rebuilds = 0;  // after the first frame, whose build every policy pays
    double update = 0.0, trace = 0.0;
    const json* worst = nullptr;  // the frame of the largest update plus trace
    PerRayCounter nIt, nTr;
    bool checked = false;
    double wrong = 0.0;
    double total() const { return update + trace; }
    bool measured() const { return failed.empty() && skipped.empty() && !rows->empty() && std::isfinite(total()); }
};

ContenderTotals totalsOf(const json& contender) {
    static const json none = json::array();
    ContenderTotals t;
    t.label = contender.at("label").get<std::string>();
    t.failed = contender.value("failed", std::string());
    t.skipped = contender.value("skipped", std::string());
    t.embree = contender.value("embree", false);
    t.rows = memberOf(contender, "rows").is_array() ? &contender.at("rows") : &none;
    for (size_t i = 0; i < t.rows->size(); ++i) {
        const json& row = (*t.rows)[i];
        const std::string action = memberOf(row, "action").is_string() ? row["action"].get<std::string>() : "";
        t.rebuilds += i > 0 && (action == "rebuild" || action == "build");
        t.update += jsonNumber(memberOf(row, "update_ms"));
        t.trace += frameTraceMs(row);
        if (!t.worst || frameCostMs(row) > frameCostMs(*t.worst)) t.worst = &row;
        t.nIt.add(row, "n_it");
        t.nTr.add(row, "n_tr");
        if (rowChecked(row)) t.checked = true, t.wrong += jsonNumber(memberOf(memberOf(row, "agreement"), "wrong"));
    }
    return t;
}

std::vector<ContenderTotals> totalsOfAll(const json& results) {
    std::vector<ContenderTotals> all;
    for (const json& contender : results.at("contenders")) all.push_back(totalsOf(contender));
    return all;
}

// The measured contender of the smallest total (among Embree's only, if `embreeOnly`); null if none.
const ContenderTotals* fastestOf(const std::vector<ContenderTotals>& all, bool embreeOnly) {
    const ContenderTotals* best = nullptr;
    for (const ContenderTotals& t : all)
        if (t.measured() && (t.embree || !embreeOnly) && (!best || t.total() < best->total())) best = &t;
    return best;
}

bool anyChecked(const json& results) {
    for (const json& contender : results.at("contenders"))
        for (const json& row : memberOf(contender, "rows"))
            if (rowChecked(row)) return true;
    return false;
}

std::string nameAndTotal(const ContenderTotals* t) {
    return t ? fmt::format("{} ({:.3f} ms)", t->label, t->total()) : std::string("none measured");
}

std::string csvLineOf(const std::vector<std::string>& cells) {
    std::string line;
    for (size_t i = 0; i < cells.size(); ++i) line += (i ? "," : "") + cells[i];
    return line + "\n";
}

}  // namespace

std::string animateSummaryTable(const json& results) {
    const std::vector<ContenderTotals> all = totalsOfAll(results);
    const ContenderTotals* best = fastestOf(all, false);
    const ContenderTotals* bestEmbree = fastestOf(all, true);
    const bool withCheck = anyChecked(results);
    std::vector<std::string> headers = {"contender",        "frames",     "rebuilds",       "T_update [ms]",
                                        "T_R p+s [ms]",     "total [ms]", "per frame [ms]", "worst frame [ms]",
                                        "SAH last / first", "N_IT / ray", "N_TR / ray",     "bytes",
                                        "/ fastest Embree", "/ fastest"};
    std::vector<std::string> alignments(headers.size(), "---:");
    alignments[0] = "---";
    if (withCheck) headers.push_back("wrong"), alignments.push_back("---:");

    std::vector<std::vector<std::string>> rows;
    for (const ContenderTotals& t : all) {
        std::vector<std::string> cells(headers.size());
        cells[0] = markdownText(t.label);
        if (!t.failed.empty() || !t.skipped.empty()) {
            cells[1] = t.failed.empty() ? "skipped: " + markdownText(t.skipped) : "failed: " + markdownText(t.failed);
            rows.push_back(cells);
            continue;
        }
        if (t.rows->empty()) {
            rows.push_back(cells);
            continue;
        }
        const json& last = t.rows->back();
        const double frames = double(t.rows->size());
        const double sah = frameSahRatio(last, *t.rows);
        cells[1] = std::to_string(t.rows->size());
        cells[2] = std::to_string(t.rebuilds);
        cells[3] = fixedCell(t.update, 3);
        cells[4] = fixedCell(t.trace, 3);
        cells[5] = fixedCell(t.total(), 3);
        cells[6] = fixedCell(t.total() / frames, 3);
        cells[7] = fmt::format("{} ({})", jsonCell(memberOf(*t.worst, "frame")), fixedCell(frameCostMs(*t.worst), 3));
        cells[8] = std::isfinite(sah) ? fmt::format("x{:.2f}", sah) : "";
        cells[9] = fixedCell(t.nIt.mean(), 2);
        cells[10] = fixedCell(t.nTr.mean(), 2);
        cells[11] = jsonCell(memberOf(last, "bytes"));
        cells[12] = bestEmbree ? fixedCell(t.total() / bestEmbree->total(), 2) : "";
        cells[13] = best ? fixedCell(t.total() / best->total(), 2) : "";
        if (withCheck) cells[14] = t.checked ? fmt::format("{:.0f}", t.wrong) : "";
        rows.push_back(cells);
    }
    return markdownTable(headers, alignments, rows) +
           fmt::format(
               "\nFastest: {}; fastest Embree contender: {}. Totals are over every measured frame, the first "
               "(the build) included; the ratios divide a total by the fastest Embree contender's and by the "
               "fastest contender's of this run.\n",
               nameAndTotal(best), nameAndTotal(bestEmbree));
}

std::string animateFramesCsv(const json& results) {
    std::vector<std::string> header = {"label",     "accel",      "policy",    "frame",    "time", "action",
                                       "update_ms", "primary_ms", "shadow_ms", "total_ms", "sah",  "sah_ratio",
                                       "epo",       "n_it",       "n_tr",      "bytes"};
    const bool withCheck = anyChecked(results);
    if (withCheck) header.push_back("wrong");
    constexpr const char* kOutcomes[] = {"failed", "skipped"};
    for (const char* outcome : kOutcomes) header.push_back(outcome);

    std::string csv = csvLineOf(header);
    for (const json& contender : results.at("contenders")) {
        const std::vector<std::string> names = {csvText(contender.at("label").get<std::string>()),
                                                csvText(jsonCell(memberOf(contender, "accel"))),
                                                csvText(jsonCell(memberOf(contender, "policy")))};
        const json& rows = memberOf(contender, "rows");
        for (const json& row : rows) {
            PerRayCounter nIt, nTr;
            nIt.add(row, "n_it");
            nTr.add(row, "n_tr");
            std::vector<std::string> cells = names;
            for (const std::string& cell :
                 {jsonCell(memberOf(row, "frame")), jsonCell(memberOf(row, "time"), "{:.6g}"),
                  jsonCell(memberOf(row, "action")), jsonCell(memberOf(row, "update_ms"), "{:.4f}"),
                  jsonCell(memberOf(memberOf(row, "primary"), "ms"), "{:.4f}"),
                  jsonCell(memberOf(memberOf(row, "shadow"), "ms"), "{:.4f}"), fixedCell(frameCostMs(row), 4),
                  jsonCell(memberOf(row, "sah"), "{:.6f}"), fixedCell(frameSahRatio(row, rows), 6),
                  jsonCell(memberOf(row, "epo"), "{:.6f}"), fixedCell(nIt.mean(), 3), fixedCell(nTr.mean(), 3),
                  jsonCell(memberOf(row, "bytes"))})
                cells.push_back(cell);
            if (withCheck) cells.push_back(jsonCell(memberOf(memberOf(row, "agreement"), "wrong")));
            cells.resize(header.size());  // neither failed nor skipped
            csv += csvLineOf(cells);
        }
        for (size_t k = 0; k < std::size(kOutcomes); ++k)
            if (contender.contains(kOutcomes[k])) {
                std::vector<std::string> cells = names;
                cells.resize(header.size());
                cells[header.size() - std::size(kOutcomes) + k] =
                    csvText(contender.at(kOutcomes[k]).get<std::string>());
                csv += csvLineOf(cells);
            }
    }
    return csv;
}

}  // namespace bvhlab
