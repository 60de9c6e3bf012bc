#include "framework/render/framebuffer.h"

#include "framework/core/available_memory.h"
#include "framework/core/error.h"

#include <bvhlab/ray.h>

#include <fmt/core.h>

namespace bvhlab {
namespace {

// What writing the PNGs and the heat map takes beside the framebuffer: an 8-bit RGB copy, stb's
// filtered rows and compressed stream, the heat map's sorted copy of the costs.
constexpr size_t kImageOutputBytesPerPixel = 16;

size_t checkedPixels(int w, int h) {
    const size_t pixels = size_t(w) * size_t(h);
    const size_t needed = Framebuffer::bytesFor(w, h) + pixels * kImageOutputBytesPerPixel;
    const AvailableMemory available = availableMemory();
    if (needed > available.bytes)
        throw InputError(
            fmt::format("a {} x {} image needs about {} (framebuffer and image outputs), but only {} is "
                        "available ({}): lower Camera::width and Camera::height",
                        w, h, formatBytes(needed), formatBytes(available.bytes), available.limit));
    return pixels;
}

}  // namespace

size_t Framebuffer::bytesFor(int w, int h) {
    const size_t perPixel = 2 * sizeof(Vec3) + 3 * sizeof(float) + sizeof(uint32_t);
    return size_t(w) * size_t(h) * perPixel;
}

Framebuffer::Framebuffer(int w, int h)
    : width(w),
      height(h),
      color(checkedPixels(w, h), Vec3(0.0f)),
      depth(size_t(w) * h, kInfinity),
      primitive(size_t(w) * h, kInvalidPrimitive),
      normal(size_t(w) * h, Vec3(0.0f)),
      traversalSteps(size_t(w) * h, 0.0f),
      intersectionTests(size_t(w) * h, 0.0f) {}

}  // namespace bvhlab
