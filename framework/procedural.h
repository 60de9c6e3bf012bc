// Generated meshes: the embedded default scene and closed shapes for tests and stress runs.
#pragma once

#include "framework/scene.h"

namespace bvhlab {

// Each appends a closed (or, for the quad, flat) mesh with outward-facing triangles and the
// given material to the scene; call scene.finalize() when done.
void addQuad(Scene& scene, const Vec3& corner, const Vec3& edge1, const Vec3& edge2, uint32_t material);
void addBox(Scene& scene, const Vec3& lower, const Vec3& upper, uint32_t material);
void addIcosphere(Scene& scene, const Vec3& center, float radius, int subdivisions, uint32_t material);
void addTorus(Scene& scene, const Vec3& center, float majorRadius, float minorRadius, int majorSegments,
              int minorSegments, uint32_t material);

// The scene `bvhlab render` shows without a scene file: a floor, boxes, a sphere, a torus
// and a mirror, lit by one light, with a camera. About 5,000 triangles.
Scene makeDefaultScene();

}  // namespace bvhlab
