// A render whose tiles are shown on a progress line.
#pragma once

#include "apps/runtime/progress.h"
#include "framework/core/accelerator.h"
#include "framework/render/camera.h"
#include "framework/render/framebuffer.h"
#include "framework/render/renderer.h"
#include "framework/scene/scene.h"

#include <string>

namespace bvhlab {

// Renders with a progress line on `progress`: phase `label`, tiles done, rays per second.
RenderStats renderWithProgress(const Scene& scene, const Accelerator& accel, const Camera& camera,
                               const RenderSettings& settings, Framebuffer& fb, Progress& progress,
                               const std::string& label);

}  // namespace bvhlab
