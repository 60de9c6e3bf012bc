// `bvhlab tradeoff`: one scene's shared inputs (ray sets, Embree's answers, the reference image)
// and the measurements of one configuration.
#include "accel/registry.h"
#include "apps/measure/tradeoff.h"
#include "apps/runtime/atomic_write.h"
#include "apps/runtime/ray_sets.h"
#include "apps/runtime/run_record.h"
#include "apps/runtime/scene_loading.h"
#include "apps/runtime/timing.h"
#include "framework/config/common_keys.h"
#include "framework/core/error.h"
#include "framework/core/timed_build.h"
#include "framework/io/image_io.h"
#include "framework/render/render_keys.h"
#include "framework/report/build_stats_json.h"
#include "framework/report/provenance.h"
#include "framework/report/query_counters_json.h"

#include <fmt/core.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <fstream>

namespace bvhlab {
namespace {

using nlohmann::json;

json finiteOrNull(double v) { return std::isfinite(v) ? json(v) : json(); }

std::vector<Vec3> renderImage(const Scene& scene, const Accelerator& accel, const CameraSpec& spec,
                              RenderSettings settings, int samples, RenderStats* stats = nullptr) {
    const Camera camera(spec);
    settings.samples = samples;
    settings.count = false;  // images and times only: the render time then has no counting calls
    Framebuffer fb(camera.width(), camera.height());
    const RenderStats s = render(scene, accel, camera, settings, fb);
    if (stats) *stats = s;
    return std::move(fb.color);
}

void writeImage(const std::filesystem::path& base, const std::vector<Vec3>& color, int width, int height) {
    Framebuffer fb(width, height);
    fb.color = color;
    writeExr(base.string() + ".exr", fb);
    writePng(base.string() + ".png", fb);
}

std::vector<Vec3> readImage(const std::filesystem::path& exr, int width, int height) {
    std::vector<Vec3> image(size_t(width) * size_t(height));
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        int w = 0, h = 0;
        const std::vector<float> channel = readExrChannel(exr, names[c], w, h);
        if (w != width || h != height)
            throw InputError(fmt::format("{}: {}x{}, expected {}x{}", exr.string(), w, h, width, height));
        for (size_t i = 0; i < image.size(); ++i) image[i][c] = channel[i];
    }
    return image;
}

}  // namespace

std::vector<int> TradeoffSettings::sppSeries() const {
    std::vector<int> series;
    for (int spp = 1; spp < maxSpp; spp *= 2) series.push_back(spp);
    series.push_back(maxSpp);
    return series;
}

json TradeoffSettings::toJson() const {
    json j = {
        {"version", 2},  // of the stored results: older ones are measured again
        {"ray_size", raySize}, {"series_size", seriesSize},        {"max_spp", maxSpp}, {"reference_spp", referenceSpp},
        {"builds", builds},    {"build_budget_ms", buildBudgetMs}, {"passes", passes},  {"threads", threads}};
    if (builders) j["mode"] = "builders";  // its results and the K series' are not each other's
    return j;
}

std::vector<AccelConfig> tradeoffConfigs(const TradeoffSettings& settings, const std::string& accels) {
    std::vector<AccelConfig> configs;
    for (const AccelConfig& config : parseAccelConfigList(accels.empty() ? ourAccelerators() : accels)) {
        if (config.label != "sahbvh") {
            configs.push_back(config);
            continue;
        }
        for (int k : settings.bins) {
            AccelConfig c = parseAccelConfig(fmt::format("sahbvh:BVH::bins={}", k));
            c.label = fmt::format("sahbvh-K{}", k);
            configs.push_back(c);
        }
    }
    configs.push_back(parseAccelConfig("embree"));
    return configs;
}

TimedBuilds timedBuilds(const Scene& scene, const AccelConfig& config, const Env& env,
                        const TradeoffSettings& settings) {
    TimedBuilds b;
    tbb::task_arena arena(settings.threads);
    double total = 0.0;
    for (int i = 0; i < settings.builds && (i == 0 || total < settings.buildBudgetMs); ++i) {
        b.accel.reset();  // one structure (and one Embree device) alive at a time
        b.accel = createAccelerator(config.name, env);
        arena.execute([&] { b.stats = timedBuild(*b.accel, scene.primitives()); });
        b.buildCpuMs.push_back(b.stats.buildCpuMs);
        b.buildMs.push_back(b.stats.buildMs);
        total += b.stats.buildMs;
    }
    return b;
}

Env tradeoffSceneEnv(const Env& sceneEnv, const TradeoffSettings& settings, int width, int height) {
    Env env = sceneEnv;
    if (width > 0) env.set(keys::Camera::width, std::to_string(width), "bvhlab tradeoff");
    if (height > 0) env.set(keys::Camera::height, std::to_string(height), "bvhlab tradeoff");
    env.set(keys::SetRayTracing::threads, std::to_string(settings.threads), "bvhlab tradeoff --threads");
    return env;
}

ImageError imageError(const std::vector<Vec3>& image, const std::vector<Vec3>& reference) {
    if (image.size() != reference.size())
        throw InputError(
            fmt::format("image of {} pixels compared with a reference of {}", image.size(), reference.size()));
    double sum = 0.0;
    ImageError e;
    for (size_t i = 0; i < image.size(); ++i) {
        bool differs = false;
        for (int c = 0; c < 3; ++c) {
            const double d =
                double(std::clamp(image[i][c], 0.0f, 1.0f)) - double(std::clamp(reference[i][c], 0.0f, 1.0f));
            sum += d * d;
            differs |= std::abs(d) > 1e-6;
        }
        e.pixelsDiffering += differs;
    }
    e.rmse = image.empty() ? 0.0 : std::sqrt(sum / (3.0 * double(image.size())));
    e.psnr = e.rmse > 0.0 ? 20.0 * std::log10(1.0 / e.rmse) : INFINITY;
    return e;
}

std::unique_ptr<Accelerator> referenceEmbree(const Scene& scene, const Env& env) {
    Env reference = env;
    reference.set(keys::SetRayTracing::threads, "0", "bvhlab tradeoff (reference)");
    auto embree = createAccelerator("embree", reference);
    embree->build(scene.primitives());
    return embree;
}

TradeoffScene prepareTradeoffScene(const std::string& id, const Env& sceneEnv, const TradeoffSettings& settings,
                                   const std::filesystem::path& sceneDir, const json& referenceKey) {
    TradeoffScene t;
    t.id = id;
    t.env = tradeoffSceneEnv(sceneEnv, settings, settings.raySize, settings.raySize);
    t.scene = loadSceneFor(t.env);
    // Embree answers the rays every configuration answers and renders the images every
    // configuration must reproduce.
    const std::unique_ptr<Accelerator> embree = referenceEmbree(t.scene, t.env);
    t.rays = sceneRaySets(t.scene, t.env, *embree);
    t.referenceHits.resize(t.rays.primary.size());
    t.referenceOccluded.resize(t.rays.shadow.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, t.rays.primary.size(), 4096), [&](const auto& range) {
        QueryCounters unused;
        for (size_t i = range.begin(); i < range.end(); ++i)
            embree->findNearest(t.rays.primary[i], t.referenceHits[i], unused);
    });
    tbb::parallel_for(tbb::blocked_range<size_t>(0, t.rays.shadow.size(), 4096), [&](const auto& range) {
        QueryCounters unused;
        for (size_t i = range.begin(); i < range.end(); ++i)
            t.referenceOccluded[i] = embree->isOccluded(t.rays.shadow[i], unused);
    });

    const Env seriesEnv = tradeoffSceneEnv(t.env, settings, settings.seriesSize, settings.seriesSize);
    t.seriesCamera = resolveCamera(t.scene, seriesEnv);
    RenderSettings seriesSettings = RenderSettings::fromEnv(seriesEnv, t.scene, t.seriesCamera);
    seriesSettings.threads = 0;
    t.embreeImage1Spp = renderImage(t.scene, *embree, t.seriesCamera, seriesSettings, 1);

    const std::filesystem::path base = sceneDir / "reference", info = sceneDir / "reference.json";
    const int w = t.seriesCamera.width, h = t.seriesCamera.height;
    if (std::filesystem::exists(info) && std::filesystem::exists(base.string() + ".exr")) {
        try {
            std::ifstream in(info);
            if (json::parse(in).at("result_key") == referenceKey) {
                t.referenceImage = readImage(base.string() + ".exr", w, h);
                fmt::print(stderr, "  {}: reference image read from {}.exr\n", id, base.string());
            }
        } catch (const std::exception& e) {
            fmt::print(stderr, "  {}: reference image not reused ({})\n", id, e.what());
        }
    }
    if (t.referenceImage.empty()) {
        const auto start = std::chrono::steady_clock::now();
        t.referenceImage = renderImage(t.scene, *embree, t.seriesCamera, seriesSettings, settings.referenceSpp);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        std::filesystem::create_directories(sceneDir);
        writeImage(base, t.referenceImage, w, h);
        writeFileAtomically(info, json{{"scene", id},
                                       {"accel", "embree"},
                                       {"width", w},
                                       {"height", h},
                                       {"samples", settings.referenceSpp},
                                       {"render_ms", ms},
                                       {"result_key", referenceKey}}
                                          .dump(2) +
                                      "\n");
        fmt::print(stderr, "  {}: reference image ({}x{}, {} spp, Embree) rendered in {:.1f} s\n", id, w, h,
                   settings.referenceSpp, ms * 1e-3);
    }
    return t;
}

namespace {

// T_R on one ray set, through the batch calls (as the tradeoff has always measured it).
json traceRaySet(const Accelerator& accel, const std::vector<Ray>& rays, const RaySetQuery& asked,
                 const TradeoffSettings& settings) {
    const bool counted = accel.hasCounters();
    const PassResult r =
        tracePasses(accel, rays, asked.anyHit, asked.coherence, settings.threads, settings.passes, QueryKind::Batch);
    const double q = std::max<double>(1.0, double(r.counters.queries));
    json result{{"rays", rays.size()}, {"t_r_us", r.usPerQuery}, {"t_r_cpu_us", r.cpuUsPerQuery}};
    result.update(queryCountersJson(r.counters, q, counted));
    return result;
}

// The answers compared with Embree's on the same rays. The first few disagreements are kept with
// the full ray (as `bvhlab raycast` reads it), so that a referee (naive, Embree's robust mode)
// can say who is right.
constexpr size_t kMismatchExamples = 5;

json rayJson(const Ray& r) {
    return json{
        {"org", {r.org.x, r.org.y, r.org.z}}, {"dir", {r.dir.x, r.dir.y, r.dir.z}}, {"tmin", r.tmin}, {"tmax", r.tmax}};
}

json hitJson(const Hit& h) { return h.found() ? json{{"t", h.t}, {"primitive", h.primitive}} : json(); }

void addPrimaryMismatches(const Accelerator& accel, const TradeoffScene& t, json& primary) {
    size_t mismatches = 0;
    json examples = json::array();
    QueryCounters unused;
    for (size_t i = 0; i < t.rays.primary.size(); ++i) {
        Hit hit;
        accel.findNearest(t.rays.primary[i], hit, unused);
        if (hitsAgree(hit, t.referenceHits[i])) continue;
        if (++mismatches <= kMismatchExamples)
            examples.push_back({{"ray_index", i},
                                {"ray", rayJson(t.rays.primary[i])},
                                {"hit", hitJson(hit)},
                                {"embree", hitJson(t.referenceHits[i])}});
    }
    primary["mismatches"] = mismatches;
    primary["mismatch_examples"] = examples;
}

void addShadowMismatches(const Accelerator& accel, const TradeoffScene& t, json& shadow) {
    size_t mismatches = 0;
    json examples = json::array();
    QueryCounters unused;
    for (size_t i = 0; i < t.rays.shadow.size(); ++i) {
        const bool occluded = accel.isOccluded(t.rays.shadow[i], unused);
        if (occluded == bool(t.referenceOccluded[i])) continue;
        if (++mismatches <= kMismatchExamples)
            examples.push_back({{"ray_index", i},
                                {"ray", rayJson(t.rays.shadow[i])},
                                {"occluded", occluded},
                                {"embree", bool(t.referenceOccluded[i])}});
    }
    shadow["mismatches"] = mismatches;
    shadow["mismatch_examples"] = examples;
}

// The spp series: time to image (the median build's and the render's) and image error; and the
// 1 spp image against Embree's.
struct SppSeries {
    json series = json::array();
    json sameImage;
};

SppSeries renderSeries(const Accelerator& accel, const TradeoffScene& t, const Env& env,
                       const TradeoffSettings& settings, double buildMedian, double buildCpuMedian) {
    RenderSettings renderSettings = RenderSettings::fromEnv(env, t.scene, t.seriesCamera);
    renderSettings.threads = settings.threads;
    SppSeries out;
    for (int spp : settings.sppSeries()) {
        RenderStats rs;
        const double cpu = processCpuMs();
        const std::vector<Vec3> image = renderImage(t.scene, accel, t.seriesCamera, renderSettings, spp, &rs);
        const double renderCpu = processCpuMs() - cpu;
        const ImageError e = imageError(image, t.referenceImage);
        out.series.push_back({{"spp", spp},
                              {"render_ms", rs.renderMs},
                              {"render_cpu_ms", renderCpu},
                              {"queries", rs.primary.counters.queries + rs.shadow.counters.queries},
                              {"time_to_image_ms", buildMedian + rs.renderMs},
                              {"time_to_image_cpu_ms", buildCpuMedian + renderCpu},
                              {"rmse", e.rmse},
                              {"psnr", finiteOrNull(e.psnr)}});
        if (spp == 1) {
            const ImageError same = imageError(image, t.embreeImage1Spp);
            out.sameImage = {{"rmse", same.rmse}, {"pixels_differing", same.pixelsDiffering}};
        }
    }
    return out;
}

}  // namespace

json measureTradeoffConfig(const TradeoffScene& t, const AccelConfig& config, const TradeoffSettings& settings) {
    const Env env = accelConfigEnv(config, t.env);
    TimedBuilds built = timedBuilds(t.scene, config, env, settings);
    const Accelerator& accel = *built.accel;
    const std::vector<double>& buildMs = built.buildMs;
    const std::vector<double>& buildCpuMs = built.buildCpuMs;
    const double buildMedian = median(buildMs), buildCpuMedian = median(buildCpuMs);

    json primary = traceRaySet(accel, t.rays.primary, kRaySetQueries[0], settings);
    json shadow = traceRaySet(accel, t.rays.shadow, kRaySetQueries[1], settings);
    addPrimaryMismatches(accel, t, primary);
    addShadowMismatches(accel, t, shadow);
    const SppSeries series = renderSeries(accel, t, env, settings, buildMedian, buildCpuMedian);

    const size_t colon = config.label.find("-K");
    json result = {{"scene", t.id},
                   {"config", config.label},
                   {"accel", config.name},
                   {"bins", colon == std::string::npos ? json() : json(std::stoi(config.label.substr(colon + 2)))},
                   {"overrides", config.overrides},
                   {"prims", t.scene.triangleCount()},
                   {"build_ms", buildMedian},
                   {"build_ms_all", buildMs},
                   {"build_cpu_ms", buildCpuMedian},
                   {"build_cpu_ms_all", buildCpuMs},
                   {"primary", primary},
                   {"shadow", shadow},
                   {"series_width", t.seriesCamera.width},
                   {"series_height", t.seriesCamera.height},
                   {"series", series.series},
                   {"same_image_1spp", series.sameImage},
                   {"provenance", provenanceJson()},
                   {"run", runJson()}};
    result.update(buildStatsJson(built.stats));
    return result;
}

}  // namespace bvhlab
