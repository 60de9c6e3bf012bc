#include "framework/render/camera.h"

#include "framework/core/error.h"
#include "framework/render/render_keys.h"

namespace bvhlab {

Camera::Camera(const CameraSpec& spec) : spec_(spec), origin_(spec.from) {
    const Vec3 forward = glm::normalize(spec.at - spec.from);
    const Vec3 right = glm::normalize(glm::cross(forward, spec.up));
    const Vec3 up = glm::cross(right, forward);
    const float halfHeight = std::tan(glm::radians(spec.fovyDegrees) * 0.5f);
    const float halfWidth = halfHeight * float(spec.width) / float(spec.height);
    right_ = right * (2.0f * halfWidth / float(spec.width));
    down_ = -up * (2.0f * halfHeight / float(spec.height));
    topLeft_ = forward - right * halfWidth + up * halfHeight;
}

Ray Camera::generateRay(float x, float y) const {
    Ray ray;
    ray.org = origin_;
    ray.dir = glm::normalize(topLeft_ + x * right_ + y * down_);
    return ray;
}

CameraSpec framingCamera(const Bounds3& bounds, float fovyDegrees, int width, int height) {
    CameraSpec spec;
    spec.fovyDegrees = fovyDegrees;
    spec.width = width;
    spec.height = height;
    if (bounds.isEmpty()) return spec;
    const Vec3 center = bounds.center();
    const float radius = std::max(0.5f * glm::length(bounds.diagonal()), 1e-6f);
    const float distance = radius / std::sin(glm::radians(fovyDegrees) * 0.5f);
    const Vec3 direction = glm::normalize(Vec3(0.35f, 0.45f, 1.0f));
    spec.from = center + direction * distance;
    spec.at = center;
    spec.up = Vec3(0.0f, 1.0f, 0.0f);
    return spec;
}

CameraSpec resolveCamera(const Scene& scene, const Env& env) {
    const float fovy = env.get(keys::Camera::fovy);
    const int width = env.get(keys::Camera::width), height = env.get(keys::Camera::height);
    CameraSpec spec = scene.camera ? *scene.camera : framingCamera(scene.bounds, fovy > 0 ? fovy : 45.0f, 512, 512);
    if (fovy > 0) spec.fovyDegrees = fovy;
    if (width > 0) spec.width = width;
    if (height > 0) spec.height = height;
    if (const auto from = env.get(keys::Camera::from)) spec.from = *from;
    if (const auto at = env.get(keys::Camera::at)) spec.at = *at;
    if (const auto up = env.get(keys::Camera::up)) spec.up = *up;
    // The one gate every render passes: a camera from a reader or a forged scene cache entry
    // is checked here as strictly as one from env.
    if (!isFinite(spec.from) || !isFinite(spec.at) || !isFinite(spec.up))
        throw InputError("camera: 'from', 'at' and 'up' must be finite");
    const Vec3 forward = spec.at - spec.from;
    if (glm::length(forward) == 0.0f || glm::length(glm::cross(forward, spec.up)) == 0.0f)
        throw InputError("camera: 'from' and 'at' coincide or 'up' is parallel to the view direction");
    if (!(spec.fovyDegrees > 0.0f && spec.fovyDegrees < 180.0f))
        throw InputError(fmt::format("camera: field of view {} degrees, expected 0 < fovy < 180", spec.fovyDegrees));
    if (spec.width < 1 || spec.height < 1 || spec.width > kMaxImageSide || spec.height > kMaxImageSide)
        throw InputError(fmt::format("camera: image {} x {}, expected 1 to {} pixels a side", spec.width, spec.height,
                                     kMaxImageSide));
    return spec;
}

}  // namespace bvhlab
