// `bvhlab tradeoff --builders`: the builders side by side. Per scene, each of our builders in
// the binary and the 8-wide layout and Embree at its three build qualities: build time, the
// tree's SAH and EPO and leaves, T_R on primary, shadow and incoherent rays, T_R against Embree
// MEDIUM and HIGH and against a bare Embree loop. Results go to DIR/<scene>/<config>.json as in
// the K series (resumable); builders.csv, builders_summary.csv and builders.md are made from
// them, with the Pareto front of build time against trace time and the rank correlation of the
// tree metrics with T_R.
//
// builders_measure.cpp: the configurations, one scene's rays, one configuration's figures;
// builders_report.cpp: the CSV files and the Markdown.
#pragma once

#include "apps/measure/tradeoff.h"

namespace bvhlab {

// The ray sets of a scene's builder comparison, in the order of every table.
inline constexpr const char* kBuilderRaySets[] = {"primary", "shadow", "incoherent"};

// The configurations of `accels` (NAME or NAME:Key=value, comma-separated; empty: every one of
// ours, ourAccelerators()); of those, sahbvh, sahbvh8, ploc8 and tdbvh also with
// BVH::optimize=insertion (labelled <name>+insertion); then embree-low, embree-medium,
// embree-high (Embree::quality through the configuration's overrides), the yardsticks.
std::vector<AccelConfig> builderConfigs(const std::string& accels);

// The configuration every ratio is taken against, and the second yardstick.
inline constexpr const char* kBuildersBaseline = "embree-medium";
inline constexpr const char* kBuildersHigh = "embree-high";

struct BuildersScene {
    std::string id;
    Env env{programKeys()};  // the scene's env with the ray camera's size and threads applied
    Scene scene;
    RaySets rays;  // at raySize, made with Embree's answers
};

BuildersScene prepareBuildersScene(const std::string& id, const Env& sceneEnv, const TradeoffSettings& settings);

// Builds (median, within buildBudgetMs), the tree's statistics and T_R per ray set; for the
// baseline also the bare Embree loop (NativeRayBatch) over the same rays.
nlohmann::json measureBuilderConfig(const BuildersScene& scene, const AccelConfig& config,
                                    const TradeoffSettings& settings);

// Reads DIR/<scene>/<config>.json, writes DIR/builders.csv, DIR/builders_summary.csv and
// DIR/builders.md, and returns the Markdown.
std::string writeBuildersReport(const std::filesystem::path& dir, const std::vector<std::string>& sceneIds,
                                const std::vector<AccelConfig>& configs, const TradeoffSettings& settings);

}  // namespace bvhlab
