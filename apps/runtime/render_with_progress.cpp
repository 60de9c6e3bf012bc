#include "apps/runtime/render_with_progress.h"

namespace bvhlab {

RenderStats renderWithProgress(const Scene& scene, const Accelerator& accel, const Camera& camera,
                               const RenderSettings& settings, Framebuffer& fb, Progress& progress,
                               const std::string& label) {
    progress.phase(label, tileCount(fb.width, fb.height));
    const RenderStats stats =
        render(scene, accel, camera, settings, fb, [&](uint64_t rays) { progress.advance(1, rays); });
    progress.finish();
    return stats;
}

}  // namespace bvhlab
