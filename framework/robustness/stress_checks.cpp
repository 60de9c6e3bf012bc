#include "framework/robustness/stress_checks.h"

#include "framework/render/camera.h"
#include "framework/render/renderer.h"

#include <fmt/format.h>

#include <algorithm>

namespace bvhlab {

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

}  // namespace bvhlab
