// Pinhole camera: rays from the eye through points on the image plane.
#pragma once

#include "framework/config/env.h"
#include "framework/scene/scene.h"

namespace bvhlab {

class Camera {
public:
    explicit Camera(const CameraSpec& spec);

    // Ray through image position (x, y) in pixels, (0, 0) the top-left corner;
    // pixel centres are at half-integers.
    Ray generateRay(float x, float y) const;
    int width() const { return spec_.width; }
    int height() const { return spec_.height; }
    const CameraSpec& spec() const { return spec_; }

private:
    CameraSpec spec_;
    Vec3 origin_, topLeft_, right_, down_;  // image plane at distance 1, spanned per pixel
};

// A view that frames the bounds from the front and a little above, the fallback when a
// scene has no camera.
CameraSpec framingCamera(const Bounds3& bounds, float fovyDegrees, int width, int height);

// The camera to render with: env keys win, then the scene's camera, then a framing view.
CameraSpec resolveCamera(const Scene& scene, const Env& env);

}  // namespace bvhlab
