#include "accel/verify/stress_checks.h"

#include "accel/registry.h"
#include "accel/verify/verify_keys.h"
#include "framework/core/timed_build.h"
#include "framework/render/camera.h"
#include "framework/render/renderer.h"

#include <fmt/format.h>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace bvhlab::verify {

TransformCheck checkTransformed(const Accelerator& accel, double scale, const DVec3& offset,
                                std::span<const Ray> baseRays, std::span<const Hit> baseHits,
                                std::span<const WatertightProbeRay> probes, int threads) {
    TransformCheck check;
    check.leaks = countLeaks(accel, probes, threads);
    QueryCounters counters;
    for (size_t i = 0; i < baseRays.size(); ++i) {
        const Hit& b = baseHits[i];
        // Only answers far from every edge stay unambiguous after the rounding of the move.
        if (!b.found() || std::min({b.u, b.v, 1.0f - b.u - b.v}) < 1e-3f) continue;
        Ray r = baseRays[i];
        r.org = Vec3(scale * DVec3(r.org) + offset);  // the direction is kept: t scales with the scene
        Hit h;
        accel.findNearest(r, h, counters);
        ++check.compared;
        bool bad = false;
        if (h.primitive != b.primitive) {
            ++check.otherPrimitive;
            bad = true;
        } else if (!(std::abs(double(h.t) / scale - double(b.t)) <= 1e-4 * double(b.t))) {
            ++check.tNotScaling;
            bad = true;
        }
        if (bad && check.examples.size() < 3)
            check.examples.push_back(fmt::format("ray {}: base hit prim {} t {:.9g}; moved: prim {} t/scale {:.9g}", i,
                                                 b.primitive, b.t, h.found() ? int64_t(h.primitive) : -1,
                                                 double(h.t) / scale));
    }
    return check;
}

AcneCheck checkShadowAcne(const Scene& scene, const Accelerator& accel, int pixels, int threads) {
    CameraSpec spec = scene.camera.value_or(CameraSpec{});
    spec.width = spec.height = pixels;
    const Camera camera(spec);
    RenderSettings settings;
    settings.threads = threads;
    settings.lights = scene.lights;
    Framebuffer lit(pixels, pixels), unshadowed(pixels, pixels);
    render(scene, accel, camera, settings, lit);
    settings.shadows = false;
    render(scene, accel, camera, settings, unshadowed);

    AcneCheck check;
    check.pixels = lit.color.size();
    const float ambient = settings.ambient * scene.materials[0].diffuse.x;
    for (size_t i = 0; i < lit.color.size(); ++i) {
        if (lit.primitive[i] == kInvalidPrimitive) continue;
        ++check.onPlane;
        if (lit.color[i] != unshadowed.color[i]) ++check.selfShadowed;
        if (!(lit.color[i].x > 1.01f * ambient)) ++check.dark;
    }
    return check;
}

std::vector<Hit> naiveAnswers(const Scene& scene, std::span<const Ray> rays, int threads) {
    const std::unique_ptr<Accelerator> naive = createAccelerator("naive", Env(verifyKeys()));
    naive->build(scene.primitives());
    std::vector<Hit> answers(rays.size());
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(size_t(0), rays.size(), [&](size_t i) {
            QueryCounters counters;
            naive->findNearest(rays[i], answers[i], counters);
        });
    });
    return answers;
}

EdgeBuildCheck checkEdgeBuild(Accelerator& accel, const Scene& scene, std::span<const Ray> rays,
                              std::span<const Hit> reference, double maxSeconds, int threads, size_t maxExamples) {
    EdgeBuildCheck check;
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] { check.stats = timedBuild(accel, scene.primitives()); });
    const BuildStats& stats = check.stats;
    // The lesser of wall and CPU time: a loaded machine stretches the one, parallel threads add
    // up in the other, and a build that blows up (quadratic, or stuck) stretches both.
    check.seconds = std::min(stats.buildMs, stats.buildCpuMs) / 1000.0;
    if (stats.primitives != scene.validPrimitives.size())
        check.problems.push_back(
            fmt::format("built over {} of {} valid primitives", stats.primitives, scene.validPrimitives.size()));
    if (stats.maxDepth && stats.depthBound && *stats.maxDepth >= *stats.depthBound)
        check.problems.push_back(fmt::format("depth {} >= {}", *stats.maxDepth, *stats.depthBound));
    if (stats.maxLeafPrimitives && stats.leafBound && *stats.maxLeafPrimitives > *stats.leafBound)
        check.problems.push_back(
            fmt::format("a leaf of {} primitives > {}", *stats.maxLeafPrimitives, *stats.leafBound));
    if (stats.bytes && *stats.bytes > kMaxBytesPerPrimitive * stats.primitives + (size_t(1) << 20))
        check.problems.push_back(fmt::format("{} bytes for {} primitives", *stats.bytes, stats.primitives));
    if (check.seconds > maxSeconds)
        check.problems.push_back(fmt::format("build took {:.1f} s (bound {:.0f} s)", check.seconds, maxSeconds));
    QueryCounters counters;
    std::vector<Hit> hits(rays.size());
    accel.findNearestBatch(rays, hits, counters, {}, RayCoherence::Incoherent);
    check.rays = rays.size();
    for (size_t i = 0; i < rays.size(); ++i) {
        if (hitsAgree(hits[i], reference[i])) continue;
        ++check.differ;
        if (check.examples.size() >= maxExamples) continue;
        const Ray& r = rays[i];
        auto answer = [](const Hit& h) {
            return h.found() ? fmt::format("t={:.9g} prim={}", h.t, h.primitive) : std::string("miss");
        };
        check.examples.push_back(fmt::format(
            "ray org=({:.9g}, {:.9g}, {:.9g}) dir=({:.9g}, {:.9g}, {:.9g}) t in [{:.9g}, {:.9g}]: {}, reference {}",
            r.org.x, r.org.y, r.org.z, r.dir.x, r.dir.y, r.dir.z, r.tmin, r.tmax, answer(hits[i]),
            answer(reference[i])));
    }
    return check;
}

}  // namespace bvhlab::verify
