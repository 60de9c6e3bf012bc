// `bvhlab tradeoff`: what the binned SAH's approximation costs and saves. Per scene and per
// configuration (tdbvh, sahbvh with K bins, sweepbvh, embree): build time, SAH cost and its gap
// to sweepbvh, T_R, time to image at 1 and at the largest sample count, hit mismatches against
// Embree on the same rays, and the image error (RMSE, PSNR against a converged reference) of a
// series of sample counts. Each configuration's results go to DIR/<scene>/<config>.json as soon
// as they are measured, so an interrupted run resumes; the CSV files and the Markdown tables
// are made from those files.
//
// tradeoff_command.cpp: the command line and the loop; tradeoff_measure.cpp: one scene's
// shared inputs and one configuration's measurements; tradeoff_report.cpp: CSV and Markdown.
// With --builders the command compares the builders instead (builders.h).
#pragma once

#include "apps/runtime/accel_config.h"
#include "apps/runtime/program_keys.h"
#include "apps/runtime/ray_sets.h"
#include "framework/config/env.h"
#include "framework/render/camera.h"
#include "framework/render/renderer.h"
#include "framework/scene/scene.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace bvhlab {

struct TradeoffSettings {
    bool quick = false;
    bool builders = false;  // the builders side by side (builders.h) instead of the K series
    std::vector<int> bins = {2, 4, 8, 16, 32, 64, 128};  // K of the sahbvh configurations
    int raySize = 400;               // T_R and mismatch ray sets: image width = height; 0 = the scene's own size
    int seriesSize = 200;            // spp series and reference: image width = height
    int maxSpp = 64;                 // the series renders 1, 2, 4, ..., maxSpp samples per pixel
    int referenceSpp = 256;          // the converged reference (Embree, all hardware threads: not timed)
    int builds = 3;                  // builds per configuration (median) ...
    double buildBudgetMs = 15000.0;  // ... fewer once their total exceeds this (the 8M-triangle scene's sweep)
    int passes = 3;                  // passes over each ray set (median)
    int threads = 1;                 // threads for every timed build, trace and render

    std::vector<int> sppSeries() const;
    // What a stored result must have been measured with to be reused.
    nlohmann::json toJson() const;
};

// The configurations of `accels` (comma-separated; empty: every one of ours, ourAccelerators()),
// a bare sahbvh among them as sahbvh-K<k> for every k (sahbvh:BVH::bins=k), then embree, the
// yardstick; labels are file names.
std::vector<AccelConfig> tradeoffConfigs(const TradeoffSettings& settings, const std::string& accels);

// What every configuration of one scene is measured against, made once per scene.
struct TradeoffScene {
    std::string id;          // the env file's stem
    Env env{programKeys()};  // the scene's env with the tradeoff's camera sizes and threads applied
    Scene scene;
    RaySets rays;                            // at raySize
    std::vector<Hit> referenceHits;          // Embree's closest hits of rays.primary
    std::vector<uint8_t> referenceOccluded;  // Embree's answers to rays.shadow
    CameraSpec seriesCamera;                 // at seriesSize
    std::vector<Vec3> referenceImage;        // referenceSpp samples per pixel at seriesSize (Embree)
    std::vector<Vec3>
        embreeImage1Spp;  // 1 sample per pixel at seriesSize (Embree): the image every structure must make
};

// The scene's env as the tradeoff uses it (camera sizes, threads), before per-configuration overrides.
Env tradeoffSceneEnv(const Env& sceneEnv, const TradeoffSettings& settings, int width, int height);

// Embree built over the scene on every hardware thread: the untimed reference whose hits make
// the ray sets and whose answers every configuration's are checked against.
std::unique_ptr<Accelerator> referenceEmbree(const Scene& scene, const Env& env);

// Loads the scene (through the scene cache), makes the ray sets and Embree's answers, and
// renders the reference image or reads it from DIR/<id>/reference.exr when it was made with
// the same settings.
TradeoffScene prepareTradeoffScene(const std::string& id, const Env& sceneEnv, const TradeoffSettings& settings,
                                   const std::filesystem::path& sceneDir, const nlohmann::json& referenceKey);

// The builds of one configuration: up to settings.builds, fewer once they have taken
// buildBudgetMs; the last structure is kept for the traces.
struct TimedBuilds {
    std::unique_ptr<Accelerator> accel;
    BuildStats stats;  // of the last build
    // Wall time and the process's CPU time over each build() (timedBuild: BuildStats::buildMs
    // and buildCpuMs).
    std::vector<double> buildMs, buildCpuMs;
};
TimedBuilds timedBuilds(const Scene& scene, const AccelConfig& config, const Env& env,
                        const TradeoffSettings& settings);

// Builds (median), traces the ray sets, counts mismatches against Embree and renders the spp
// series: the JSON stored in DIR/<scene>/<config>.json.
nlohmann::json measureTradeoffConfig(const TradeoffScene& scene, const AccelConfig& config,
                                     const TradeoffSettings& settings);

// RMSE of the colours clamped to [0, 1] (over pixels and channels), and PSNR = 20 log10(1 / RMSE).
struct ImageError {
    double rmse = 0.0;
    double psnr = 0.0;           // +inf for identical images
    size_t pixelsDiffering = 0;  // any channel differs by more than 1e-6
};
ImageError imageError(const std::vector<Vec3>& image, const std::vector<Vec3>& reference);

// "Structures, with their own settings:" and a line per configuration measured into
// DIR/<scene>/<config>.json: its own settings and its plugin, as its result key records them
// (result_key.h: describeStructure).
std::string structuresMeasured(const std::filesystem::path& dir, const std::vector<std::string>& sceneIds,
                               const std::vector<AccelConfig>& configs);

// Reads DIR/<scene>/<config>.json for every scene and configuration (missing ones are left
// out), writes DIR/tradeoff.csv, DIR/image_error.csv and DIR/tradeoff.md, and returns the
// Markdown.
std::string writeTradeoffReport(const std::filesystem::path& dir, const std::vector<std::string>& sceneIds,
                                const std::vector<AccelConfig>& configs, const TradeoffSettings& settings);

}  // namespace bvhlab
