// What a user reads of `bvhlab animate`: the summary table and the per-frame CSV, made from the
// results file alone (DIR/animate.json), so that they can be made again from it without running
// anything.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace bvhlab {

// A Markdown table, a row per contender (structure under a policy): frames measured, rebuilds
// after the first frame, the totals of T_update, of T_R (primary and shadow rays) and of both, the
// mean per frame, the worst frame, the SAH of the last frame over the first's, N_IT and N_TR per
// ray, the bytes at the last frame, and the total over the fastest Embree contender's and over
// the fastest contender's; with the answers checked, the wrong ones. Totals include the first
// frame's build. A line under it names the fastest contender and the fastest Embree contender.
// A contender that failed, or was skipped (it cannot run its policy), is a row with the reason,
// outside every ratio.
std::string animateSummaryTable(const nlohmann::json& results);

// A CSV row per contender and measured frame: label,accel,policy,frame,time,action,update_ms,
// primary_ms,shadow_ms,total_ms,sah,sah_ratio (to the contender's first frame),epo,n_it,n_tr
// (per ray, primary and shadow together),bytes, then wrong where answers were checked, failed and
// skipped (the reason, on a row of its own after the frames the contender measured). Empty cells
// where a figure is null.
std::string animateFramesCsv(const nlohmann::json& results);

}  // namespace bvhlab
