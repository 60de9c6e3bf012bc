// Generated meshes: the embedded default scene and closed shapes for tests and stress runs.
#pragma once

#include "framework/scene/scene.h"

namespace bvhlab {

// A triangle with three vertices of its own (shared with no other triangle), material 0.
void addLooseTriangle(Scene& scene, const Vec3& a, const Vec3& b, const Vec3& c);

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
