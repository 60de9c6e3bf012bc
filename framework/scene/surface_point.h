// Where a closest-hit answer met the scene, as shading and secondary rays need it, for every
// primitive kind: the point, its normals, and origins for rays that leave it.
#pragma once

#include "framework/core/ray_offset.h"
#include "framework/scene/scene.h"

namespace bvhlab {

struct SurfacePoint {
    Vec3 position;
    Vec3 geometricNormal;  // unit, on the side the ray came from
    Vec3 shadingNormal;    // unit, same side: interpolated vertex normals where the mesh has them
    // The ray met the outside: the side the primitive's own normal points to (a triangle's
    // winding, away from a sphere's centre or a cone's axis).
    bool outside = true;
    float magnitude = 0.0f;  // the largest coordinate of the surface, for offsetRayOrigin

    // Origins for a ray leaving to the side the ray came from (shadow, reflection), or through
    // the surface (refraction).
    Vec3 originAbove() const { return offsetRayOrigin(position, geometricNormal, magnitude); }
    Vec3 originBelow() const { return offsetRayOrigin(position, -geometricNormal, magnitude); }
};

// `hit` must be found() and answer `ray` over `scene`'s primitives.
SurfacePoint surfaceAt(const Scene& scene, const Ray& ray, const Hit& hit);

}  // namespace bvhlab
