#include "framework/render/render_keys.h"

#include "framework/scene/scene.h"

namespace bvhlab {

static_assert(kMaxImageSide == 16384, "Camera::width and Camera::height are declared with this range");

void registerRenderKeys(EnvRegistry& r) {
    for (const IntKey& key :
         {keys::SetRayTracing::cntSamples, keys::SetRayTracing::depthLimit, keys::Camera::width, keys::Camera::height})
        r.add(key);
    r.add(keys::SetRayTracing::shadows);
    for (const FloatKey& key : {keys::Render::ambient, keys::Lights::intensity, keys::Camera::fovy}) r.add(key);
    for (const Vec3Key& key : {keys::Scene::background, keys::Camera::from, keys::Camera::at, keys::Camera::up})
        r.add(key);
    r.add(keys::Lights::positions);
}

}  // namespace bvhlab
