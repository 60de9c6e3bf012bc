#include "apps/animate/animation_run.h"

#include "accel/registry.h"
#include "accel/verify/oracle.h"
#include "apps/runtime/app_keys.h"
#include "apps/runtime/progress.h"
#include "apps/runtime/ray_sets.h"
#include "apps/runtime/timing.h"
#include "apps/runtime/trace_rays.h"
#include "framework/config/common_keys.h"
#include "framework/core/error.h"
#include "framework/core/parse_number.h"
#include "framework/scene/scene_instances.h"

#include <fmt/core.h>

#include <algorithm>
#include <optional>

namespace bvhlab {

std::vector<int> parseFrames(const std::string& text, int count, const std::string& source) {
    if (text == "all") {
        std::vector<int> all(size_t(count), 0);
        for (int i = 0; i < count; ++i) all[size_t(i)] = i;
        return all;
    }
    std::vector<std::string> parts(1);
    for (char ch : text) {
        if (ch == ':')
            parts.emplace_back();
        else
            parts.back().push_back(ch);
    }
    int first = 0, end = 0, stride = 1;
    if (parts.size() < 2 || parts.size() > 3 || !parseNumber(parts[0], first) || !parseNumber(parts[1], end) ||
        (parts.size() == 3 && (!parseNumber(parts[2], stride) || stride < 1)))
        throw InputError(fmt::format("{} {}: not all, FIRST:END or FIRST:END:STRIDE", source, text));
    if (first < 0 || end > count || first >= end)
        throw InputError(fmt::format("{} {}: the scene has frames 0 to {}", source, text, count - 1));
    std::vector<int> frames;
    for (int f = first; f < end; f += stride) frames.push_back(f);
    return frames;
}

namespace {

nlohmann::json optionalNumber(const std::optional<double>& value) {
    return value ? nlohmann::json(*value) : nlohmann::json();
}

nlohmann::json updateRow(int frame, float time, const FrameUpdate& update) {
    const BuildStats& s = update.stats;
    return {{"frame", frame},
            {"time", time},
            {"action", toString(update.action)},
            {"update_ms", s.buildMs},
            {"update_cpu_ms", s.buildCpuMs},
            {"sah", s.sah ? nlohmann::json(s.sah->cost) : nlohmann::json()},
            {"epo", optionalNumber(s.epo)},
            {"bytes", s.bytes ? nlohmann::json(*s.bytes) : nlohmann::json()}};
}

// The rays' counters per ray, or null where the structure does not count.
nlohmann::json traceColumns(size_t rays, double ms, const QueryCounters& counters) {
    const bool counted = counters.counting && rays > 0;
    return {{"rays", rays},
            {"ms", ms},
            {"n_it", counted ? nlohmann::json(double(counters.intersectionTests) / double(rays)) : nlohmann::json()},
            {"n_tr", counted ? nlohmann::json(double(counters.traversalSteps) / double(rays)) : nlohmann::json()}};
}

// The decider where a contender and the reference (Embree) differ: the double-precision brute
// force over the triangles (verify::Oracle); in a scene with spheres or cones, where an answer or
// the truth may be a quadric, our brute force over everything (naive, the quadrics' tests in
// double) decides.
class FrameJudge {
public:
    explicit FrameJudge(const PrimitiveSet& prims, const Env& env)
        : oracle_(PrimitiveSet{prims.triangles, prims.validTriangles()}) {
        if (!prims.hasQuadrics()) return;
        naive_ = createAccelerator("naive", env);
        naive_->build(prims);
    }

    bool wrongNearest(const Ray& ray, const Hit& answer) const {
        if (!naive_) return oracle_.judge(ray, answer).verdict == verify::Verdict::Wrong;
        QueryCounters counters;
        Hit truth;
        naive_->findNearest(ray, truth, counters);
        return !hitsAgree(answer, truth);
    }
    // An any-hit answer is judged as the structure's closest hit along the ray would be: a
    // shadow ray that grazes an edge is then a tie, as a primary ray's would be.
    bool wrongOccluded(const Accelerator& accel, const Ray& ray, bool answer) const {
        QueryCounters counters;
        if (naive_) return answer != naive_->isOccluded(ray, counters);
        Hit hit;
        if (answer && !accel.findNearest(ray, hit, counters)) return true;
        return oracle_.judge(ray, hit).verdict == verify::Verdict::Wrong;
    }

private:
    verify::Oracle oracle_;
    std::unique_ptr<Accelerator> naive_;
};

// The contender's answers against the reference's; where they differ, the judge decides whether
// the contender is wrong or the two tie.
nlohmann::json checkAnswers(const Accelerator& accel, const Accelerator& reference, const FrameJudge& judge,
                            const RaySets& rays, int threads) {
    size_t wrong = 0, ties = 0;
    std::vector<Hit> hits(rays.primary.size()), expected(rays.primary.size());
    traceRays(accel, rays.primary, false, RayCoherence::Coherent, threads, false,
              {.hits = hits, .occluded = {}, .costs = {}});
    traceRays(reference, rays.primary, false, RayCoherence::Coherent, threads, false,
              {.hits = expected, .occluded = {}, .costs = {}});
    for (size_t i = 0; i < hits.size(); ++i)
        if (!hitsAgree(hits[i], expected[i])) (judge.wrongNearest(rays.primary[i], hits[i]) ? wrong : ties) += 1;
    std::vector<uint8_t> occluded(rays.shadow.size()), expectedOccluded(rays.shadow.size());
    traceRays(accel, rays.shadow, true, RayCoherence::Coherent, threads, false,
              {.hits = {}, .occluded = occluded, .costs = {}});
    traceRays(reference, rays.shadow, true, RayCoherence::Coherent, threads, false,
              {.hits = {}, .occluded = expectedOccluded, .costs = {}});
    for (size_t i = 0; i < occluded.size(); ++i)
        if (occluded[i] != expectedOccluded[i])
            (judge.wrongOccluded(accel, rays.shadow[i], occluded[i]) ? wrong : ties) += 1;
    return {{"checked", hits.size() + occluded.size()}, {"wrong", wrong}, {"ties", ties}};
}

// The adaptive policy reads its structure's statistics in its update time, to decide by their
// SAH: our BVHs' EPO, which it does not decide by, is left out of them.
void withoutEpo(Env& env, const std::string& accel) {
    const char* const kEpoKey = "BVH::epoMaxTriangles";
    const std::vector<std::string> readers = acceleratorsReading(kEpoKey);
    if (std::find(readers.begin(), readers.end(), accel) != readers.end())
        env.set(kEpoKey, "0", "adaptive decides by the SAH alone");
}

}  // namespace

struct AnimationRun::Contender {
    AccelConfig config;
    Env env;
    std::unique_ptr<AnimatedStructure> structure;
    nlohmann::json result;  // as docs/animation.md describes a contender
    std::vector<double> primaryMs, shadowMs;
};

AnimationRun::AnimationRun(AnimatedScene& animated, const Env& base, AnimationSettings settings)
    : animated_(animated), base_(base), settings_(std::move(settings)) {
    if (settings_.frames.empty()) throw InputError("an animation run needs at least one frame");
    animated_.setTime(animated_.frameTime(settings_.frames.front()));
}

AnimationRun::~AnimationRun() = default;

void AnimationRun::addContender(const AccelConfig& config, const std::string& policy) {
    auto c = std::make_unique<Contender>(Contender{config, accelConfigEnv(config, base_), {}, {}, {}, {}});
    c->env.set(keys::Animate::policy, policy, "the contender's policy");
    if (policy == "adaptive") withoutEpo(c->env, config.name);
    c->env.set(keys::SetRayTracing::threads, std::to_string(settings_.threads), "the animation's threads");
    c->result = {{"label", config.label + "/" + policy},
                 {"accel", config.label},
                 {"policy", policy},
                 {"policy_keys",
                  {{keys::Animate::sahGrowth.name(), c->env.get(keys::Animate::sahGrowth)},
                   {keys::Animate::rebuildEvery.name(), c->env.get(keys::Animate::rebuildEvery)}}},
                 {"embree", config.name == "embree"},
                 {"rows", nlohmann::json::array()}};
    contenders_.push_back(std::move(c));
}

template <typename Body>
void AnimationRun::guard(Contender& c, Body&& body) {
    if (!c.structure && c.result["rows"].size() > 0) return;
    try {
        body();
    } catch (const NoUpdateError& e) {
        c.result["skipped"] = e.what();
        c.structure.reset();
        fmt::print(stderr, "{}: skipped: {}\n", c.result["label"].get<std::string>(), e.what());
    } catch (const std::exception& e) {
        c.result["failed"] = e.what();
        c.structure.reset();
        fmt::print(stderr, "{}: failed: {}\n", c.result["label"].get<std::string>(), e.what());
    }
}

void AnimationRun::run(const AfterFrame& afterFrame) {
    const std::vector<int>& frames = settings_.frames;
    for (const auto& c : contenders_)
        guard(*c, [&] {
            c->structure = std::make_unique<AnimatedStructure>(animated_, c->config.name, c->env);
            c->result["rows"].push_back(updateRow(frames[0], animated_.time(), c->structure->start()));
        });
    Progress progress;
    for (size_t f = 0; f < frames.size(); ++f) {
        progress.phase(fmt::format("{}: frame {} ({} of {})", animated_.scene.name, frames[f], f + 1, frames.size()));
        const bool validChanged = f > 0 && animated_.setTime(animated_.frameTime(frames[f]));
        measureFrame(f, validChanged, afterFrame);
        progress.finish();
    }
}

void AnimationRun::measureFrame(size_t f, bool validChanged, const AfterFrame& afterFrame) {
    const int frame = settings_.frames[f];
    const float time = animated_.time();
    const int threads = settings_.threads;
    std::vector<Contender*> active;
    for (const auto& c : contenders_)
        if (c->structure) active.push_back(c.get());
    // The order turns every frame, so that no contender always runs first on a cold cache.
    if (!active.empty()) std::rotate(active.begin(), active.begin() + std::ptrdiff_t(f % active.size()), active.end());
    if (f > 0)
        for (Contender* c : active)
            guard(*c,
                  [&] { c->result["rows"].push_back(updateRow(frame, time, c->structure->advance(validChanged))); });

    // The frame's rays, from Embree's hits (untimed): every contender traces the same ones.
    const std::unique_ptr<Accelerator> reference = createAccelerator("embree", base_);
    reference->build(animated_.scene.primitives());
    const RaySets rays = sceneRaySets(animated_.scene, base_, *reference);
    active.erase(std::remove_if(active.begin(), active.end(), [](const Contender* c) { return !c->structure; }),
                 active.end());
    for (Contender* c : active) c->primaryMs.clear(), c->shadowMs.clear();
    std::vector<QueryCounters> primaryCounts(active.size()), shadowCounts(active.size());
    for (int round = 0; round < settings_.rounds; ++round)
        for (size_t k = 0; k < active.size(); ++k) {
            const size_t slot = (k + size_t(round)) % active.size();
            Contender& c = *active[slot];
            guard(c, [&] {
                const Accelerator& accel = c.structure->accelerator();
                const PassResult primary = tracePasses(accel, rays.primary, false, RayCoherence::Coherent, threads, 1,
                                                       QueryKind::Batch, round == 0);
                const PassResult shadow = tracePasses(accel, rays.shadow, true, RayCoherence::Coherent, threads, 1,
                                                      QueryKind::Batch, round == 0);
                c.primaryMs.push_back(primary.usPerQuery * double(rays.primary.size()) * 1e-3);
                c.shadowMs.push_back(shadow.usPerQuery * double(rays.shadow.size()) * 1e-3);
                if (round == 0) primaryCounts[slot] = primary.counters, shadowCounts[slot] = shadow.counters;
            });
        }
    std::optional<FrameJudge> judge;
    if (settings_.check) judge.emplace(animated_.scene.primitives(), base_);
    for (size_t k = 0; k < active.size(); ++k) {
        Contender& c = *active[k];
        if (!c.structure) continue;
        nlohmann::json& row = c.result["rows"].back();
        row["primary"] = traceColumns(rays.primary.size(), median(c.primaryMs), primaryCounts[k]);
        row["shadow"] = traceColumns(rays.shadow.size(), median(c.shadowMs), shadowCounts[k]);
        if (judge)
            guard(c, [&] {
                row["agreement"] = checkAnswers(c.structure->accelerator(), *reference, *judge, rays, threads);
            });
    }
    if (afterFrame) afterFrame(frame, *reference);
}

nlohmann::json AnimationRun::header(const std::filesystem::path& file) const {
    const Scene& scene = animated_.scene;
    return {{"scene",
             {{"id", file.stem().string()},
              {"name", scene.name},
              {"file", file.string()},
              {"frame_count", animated_.frameCount},
              {"start_time", animated_.startTime},
              {"end_time", animated_.endTime},
              {"triangles", scene.triangleCount()},
              {"moving_primitives", animated_.movingPrimitives().size()},
              {"instances", SceneInstances(animated_).instances().size()}}},
            {"frames", settings_.frames},
            {"threads", settings_.threads},
            {"rounds", settings_.rounds}};
}

nlohmann::json AnimationRun::contenders() const {
    nlohmann::json all = nlohmann::json::array();
    for (const auto& c : contenders_) all.push_back(c->result);
    return all;
}

size_t AnimationRun::failedCount() const {
    return size_t(std::count_if(contenders_.begin(), contenders_.end(),
                                [](const auto& c) { return c->result.contains("failed"); }));
}

}  // namespace bvhlab
