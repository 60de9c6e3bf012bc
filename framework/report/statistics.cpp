#include "framework/report/statistics.h"

#include "framework/report/build_stats_json.h"
#include "framework/report/query_counters_json.h"

#include <fmt/format.h>

namespace bvhlab {
namespace {

template <typename T>
std::string orNa(const std::optional<T>& value, const char* format) {
    return value ? fmt::format(fmt::runtime(format), *value) : "n/a";
}

double perQuery(uint64_t total, uint64_t queries) { return queries ? double(total) / double(queries) : 0.0; }

// Per-query figures are null where nothing was traced (e.g. shadows off) or nothing counted.
nlohmann::json queryJson(const QueryStats& q, bool hasCounters) {
    const bool traced = q.counters.queries > 0;
    nlohmann::json j = {{"queries", q.counters.queries}};
    j["t_r_us"] = traced ? nlohmann::json(q.usPerQuery()) : nlohmann::json();
    j.update(queryCountersJson(q.counters, double(q.counters.queries), traced && hasCounters));
    return j;
}

}  // namespace

std::string formatStatsTable(const StatsRow& row) {
    const BuildStats& b = row.build;
    // The counters with a column (kQueryCounters) stand between T_R and N_Q.
    std::string out = fmt::format("{:<14} {:<9} {:>9} {:>9} {:>9} {:>10} {:>8} {:>9} {:>9}", "scene", "accel", "#Prims",
                                  "#Leaves", "#Nodes", "SAH", "EPO", "T_B ms", "T_R us");
    for (const QueryCounter& c : kQueryCounters)
        if (c.column) out += fmt::format(" {:>8}", c.column);
    out += fmt::format(" {:>10} {:>10}\n", "N_Q", "render ms");
    auto line = [&](const char* label, const QueryStats& q, bool first) {
        const bool traced = q.counters.queries > 0, counted = traced && row.hasCounters;
        const std::string tr = traced ? fmt::format("{:.3f}", q.usPerQuery()) : "n/a";
        out += fmt::format("{:<14} {:<9} {:>9} {:>9} {:>9} {:>10} {:>8} {:>9} {:>9}", first ? row.scene : label,
                           first ? row.accel : "", first ? fmt::format("{}", row.prims) : "",
                           first ? orNa(b.leaves, "{}") : "", first ? orNa(b.nodes, "{}") : "",
                           first ? (b.sah ? fmt::format("{:.3f}", b.sah->cost) : "n/a") : "",
                           first ? orNa(b.epo, "{:.3f}") : "", first ? fmt::format("{:.1f}", b.buildMs) : "", tr);
        for (const QueryCounter& c : kQueryCounters)
            if (c.column)
                out += fmt::format(
                    " {:>8}",
                    counted ? fmt::format("{:.2f}", perQuery(q.counters.*c.count, q.counters.queries)) : "n/a");
        out += fmt::format(" {:>10} {:>10}\n", q.counters.queries,
                           first ? fmt::format("{:.1f}", row.render.renderMs) : "");
    };
    // The first line is the closest-hit queries (camera rays and mirror bounces), the second
    // the shadow rays alone (any-hit queries toward the lights), as the report's rows.
    line("primary", row.render.primary, true);
    line("  shadow rays", row.render.shadow, false);
    // Shadow rays not cast: those whose light is behind the surface, and with shadows off the rest.
    const std::string shadowsNotCast =
        row.render.shadowRaysSkippedDisabled > 0
            ? fmt::format("shadows off: no shadow rays cast ({} toward lights, {} with the light behind the surface)",
                          row.render.shadowRaysSkippedDisabled, row.render.shadowRaysSkippedBackfacing)
            : fmt::format("shadow rays not cast: {} (the light behind the surface)",
                          row.render.shadowRaysSkippedBackfacing);
    out += fmt::format(
        "degenerate, skipped: {} triangles, {} spheres, {} cones/cylinders, {} polygons; {}; bounces "
        "cut by depthLimit: {}; threads: {}",
        row.load.degenerateTriangles, row.load.degenerateSpheres, row.load.degenerateCones, row.load.skippedPolygons,
        shadowsNotCast, row.render.bouncesSkipped, row.render.threads);
    if (b.sah) out += fmt::format("; SAH and EPO with C_trav={} C_isect={}", b.sah->cTraversal, b.sah->cIntersect);
    for (const NamedFigure& f : b.figures)
        out += fmt::format("\n{} {}: {} ({})", row.accel, f.name, f.value, f.meaning);
    return out;
}

nlohmann::json statsJson(const StatsRow& row) {
    const BuildStats& b = row.build;
    nlohmann::json j = {
        {"scene", row.scene},
        {"accel", row.accel},
        {"prims", row.prims},
        {"degenerate", row.load.degenerateTriangles},
        {"degenerate_spheres", row.load.degenerateSpheres},
        {"degenerate_cones", row.load.degenerateCones},
        {"skipped_polygons", row.load.skippedPolygons},
        {"ear_clipped_polygons", row.load.earClippedPolygons},
        {"build_ms", b.buildMs},
        {"render_ms", row.render.renderMs},
        {"threads", row.render.threads},
        {"primary", queryJson(row.render.primary, row.hasCounters)},
        {"shadow", queryJson(row.render.shadow, row.hasCounters)},
        {"skipped",
         {{"shadow_disabled", row.render.shadowRaysSkippedDisabled},
          {"shadow_backfacing", row.render.shadowRaysSkippedBackfacing},
          {"bounces", row.render.bouncesSkipped}}},
    };
    j.update(buildStatsJson(b));
    return j;
}

}  // namespace bvhlab
