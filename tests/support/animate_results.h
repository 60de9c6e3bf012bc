// A small results file of `bvhlab animate` (DIR/animate.json; apps/animate/animate_report.h), written
// by hand so that its totals can be worked out on paper: three frames, two of our contenders (a
// refit, and an adaptive one that refits alike but rebuilds at frame 20), two of Embree's (no SAH,
// no counters; one not checked; one skipped: it cannot refit) and one that failed after a partial
// first frame. With every update and trace time,
// per contender:
//   sahbvh8/refit       update 30+2+2 = 34,    trace 15+18+21 = 54, total  88, worst frame 0 (45)
//   sahbvh8/adaptive    update 30+2+120 = 152, trace 15+18+15 = 48, total 200, worst frame 20 (135)
//   embree-refit/refit  update 50+3+3 = 56,    trace 12+14+15 = 41, total  97, worst frame 0 (62)
//   embree-low/rebuild  update 20+20+20 = 60,  trace 18+18+19 = 55, total 115, worst frame 20 (39)
// N_IT per ray of ours: (30 x 100 primary + 15 x 50 shadow rays) / 150 = 25; N_TR (6, 3): 5.
#pragma once

#include <nlohmann/json.hpp>

namespace bvhlab::test {

inline nlohmann::json smallAnimateResults() {
    nlohmann::json results = nlohmann::json::parse(R"({
  "scene": {"id": "toy", "name": "toy", "frame_count": 21, "start_time": 0.0, "end_time": 2.0},
  "frames": [0, 10, 20], "threads": 1, "rounds": 1, "width": 16, "height": 16, "lights": 1,
  "contenders": [
    {"label": "sahbvh8/refit", "accel": "sahbvh8", "policy": "refit", "embree": false, "rows": [
      {"frame": 0, "time": 0.0, "action": "build", "update_ms": 30.0,
       "primary": {"rays": 100, "ms": 10.0, "n_it": 30.0, "n_tr": 6.0},
       "shadow": {"rays": 50, "ms": 5.0, "n_it": 15.0, "n_tr": 3.0},
       "sah": 50.0, "epo": 10.0, "bytes": 1000, "agreement": {"checked": 150, "wrong": 0, "ties": 0}},
      {"frame": 10, "time": 1.0, "action": "refit", "update_ms": 2.0,
       "primary": {"rays": 100, "ms": 12.0, "n_it": 30.0, "n_tr": 6.0},
       "shadow": {"rays": 50, "ms": 6.0, "n_it": 15.0, "n_tr": 3.0},
       "sah": 55.0, "epo": 11.0, "bytes": 1000, "agreement": {"checked": 150, "wrong": 1, "ties": 0}},
      {"frame": 20, "time": 2.0, "action": "refit", "update_ms": 2.0,
       "primary": {"rays": 100, "ms": 14.0, "n_it": 30.0, "n_tr": 6.0},
       "shadow": {"rays": 50, "ms": 7.0, "n_it": 15.0, "n_tr": 3.0},
       "sah": 60.0, "epo": 12.0, "bytes": 1000, "agreement": {"checked": 150, "wrong": 0, "ties": 1}}]},
    {"label": "embree-refit/refit", "accel": "embree-refit", "policy": "refit", "embree": true, "rows": [
      {"frame": 0, "time": 0.0, "action": "build", "update_ms": 50.0,
       "primary": {"rays": 100, "ms": 8.0, "n_it": null, "n_tr": null},
       "shadow": {"rays": 50, "ms": 4.0, "n_it": null, "n_tr": null},
       "sah": null, "epo": null, "bytes": 2000, "agreement": {"checked": 150, "wrong": 0, "ties": 0}},
      {"frame": 10, "time": 1.0, "action": "refit", "update_ms": 3.0,
       "primary": {"rays": 100, "ms": 9.0, "n_it": null, "n_tr": null},
       "shadow": {"rays": 50, "ms": 5.0, "n_it": null, "n_tr": null},
       "sah": null, "epo": null, "bytes": 2000, "agreement": {"checked": 150, "wrong": 0, "ties": 0}},
      {"frame": 20, "time": 2.0, "action": "refit", "update_ms": 3.0,
       "primary": {"rays": 100, "ms": 10.0, "n_it": null, "n_tr": null},
       "shadow": {"rays": 50, "ms": 5.0, "n_it": null, "n_tr": null},
       "sah": null, "epo": null, "bytes": 2000, "agreement": {"checked": 150, "wrong": 0, "ties": 0}}]},
    {"label": "embree-low/rebuild", "accel": "embree-low", "policy": "rebuild", "embree": true, "rows": [
      {"frame": 0, "time": 0.0, "action": "build", "update_ms": 20.0,
       "primary": {"rays": 100, "ms": 12.0, "n_it": null, "n_tr": null},
       "shadow": {"rays": 50, "ms": 6.0, "n_it": null, "n_tr": null}, "sah": null, "epo": null, "bytes": 1500},
      {"frame": 10, "time": 1.0, "action": "rebuild", "update_ms": 20.0,
       "primary": {"rays": 100, "ms": 12.0, "n_it": null, "n_tr": null},
       "shadow": {"rays": 50, "ms": 6.0, "n_it": null, "n_tr": null}, "sah": null, "epo": null, "bytes": 1500},
      {"frame": 20, "time": 2.0, "action": "rebuild", "update_ms": 20.0,
       "primary": {"rays": 100, "ms": 13.0, "n_it": null, "n_tr": null},
       "shadow": {"rays": 50, "ms": 6.0, "n_it": null, "n_tr": null}, "sah": null, "epo": null, "bytes": 1500}]},
    {"label": "embree-low/refit", "accel": "embree-low", "policy": "refit", "embree": true,
     "skipped": "Embree at low quality has no refit", "rows": []},
    {"label": "kdtree/rebuild", "accel": "kdtree", "policy": "rebuild", "embree": false,
     "failed": "threw: kdtree | cannot be updated, no refit",
     "rows": [{"frame": 0, "time": 0.0, "action": "build", "update_ms": 40.0}]}
  ]
})");
    // The adaptive policy refits as sahbvh8/refit does until the tree's SAH has grown too far.
    nlohmann::json adaptive = results["contenders"][0];
    adaptive["label"] = "sahbvh8/adaptive";
    adaptive["policy"] = "adaptive";
    adaptive["rows"][2].update(nlohmann::json::parse(R"({"action": "rebuild", "update_ms": 120.0, "sah": 51.0,
        "epo": 10.0, "bytes": 1200, "agreement": {"checked": 150, "wrong": 0, "ties": 0}})"));
    adaptive["rows"][2]["primary"]["ms"] = 10.0;
    adaptive["rows"][2]["shadow"]["ms"] = 5.0;
    results["contenders"].insert(results["contenders"].begin() + 1, adaptive);
    return results;
}

}  // namespace bvhlab::test
