// A scene whose primitives moved, as an animation moves them, for checking updates
// (Accelerator::update): the part of the scene beyond its centre along x turned and shifted (a
// rigid motion, blended in across a band), then one vertex in four pushed by a fraction of its
// shortest edge. Every vertex, sphere centre and cone end moves as a function of where it was,
// so meshes that share positions stay closed.
// Deterministic, and the primitive index space and the valid list stay the scene's: a
// primitive the motion would make degenerate keeps its place.
#pragma once

#include "framework/scene/scene.h"

namespace bvhlab::verify {

Scene movedScene(const Scene& scene);

}  // namespace bvhlab::verify
