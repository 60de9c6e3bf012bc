#include "framework/framebuffer.h"

#include "framework/ray.h"

namespace bvhlab {

Framebuffer::Framebuffer(int w, int h)
    : width(w), height(h), color(size_t(w) * h, Vec3(0.0f)), depth(size_t(w) * h, kInfinity),
      primitive(size_t(w) * h, kInvalidPrimitive), normal(size_t(w) * h, Vec3(0.0f)),
      traversalSteps(size_t(w) * h, 0.0f), intersectionTests(size_t(w) * h, 0.0f) {}

}  // namespace bvhlab
