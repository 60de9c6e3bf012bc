// The env keys the renderer (renderer.cpp) and the camera (camera.cpp) read, besides
// SetRayTracing::threads (framework/config/common_keys.h).
#pragma once

#include "framework/config/common_keys.h"

namespace bvhlab {

namespace keys::SetRayTracing {
inline constexpr IntKey cntSamples{"SetRayTracing::cntSamples", "1", 1, 65536,
                                   "samples per pixel; above 1 they are stratified jittered"};
inline constexpr IntKey depthLimit{"SetRayTracing::depthLimit", "1", 1, 64,
                                   "path length: 1 = primary rays only, more allows mirror bounces"};
inline constexpr BoolKey shadows{"SetRayTracing::shadows", "true", "cast a shadow ray per light and shading point"};
}  // namespace keys::SetRayTracing

namespace keys::Render {
inline constexpr FloatKey ambient{"Render::ambient", "0.05", 0, 1,
                                  "ambient term so that shadowed surfaces stay visible"};
}

namespace keys::Scene {
inline constexpr Vec3Key background{"Scene::background", "",
                                    "background colour on a miss; empty = the scene's, else dark blue"};
}

namespace keys::Lights {
inline constexpr Vec3ListKey positions{"Lights::positions", "",
                                       "point lights 'x y z, x y z'; empty = the scene's, else one above the camera"};
inline constexpr FloatKey intensity{
    "Lights::intensity", "1", 0, 1e30,
    "irradiance each env light gives at the scene centre (falls off with distance squared)"};
}  // namespace keys::Lights

namespace keys::Camera {
inline constexpr Vec3Key from{"Camera::from", "",
                              "eye position; empty = the scene's camera, else a view framing the scene"};
inline constexpr Vec3Key at{"Camera::at", "", "point looked at; empty = as Camera::from"};
inline constexpr Vec3Key up{"Camera::up", "", "up direction; empty = the scene's, else +y"};
inline constexpr FloatKey fovy{"Camera::fovy", "0", 0, 179,
                               "vertical field of view in degrees; 0 = the scene's, else 45"};
inline constexpr IntKey width{"Camera::width", "0", 0, 16384, "image width in pixels; 0 = the scene's, else 512"};
inline constexpr IntKey height{"Camera::height", "0", 0, 16384, "image height in pixels; 0 = the scene's, else 512"};
}  // namespace keys::Camera

void registerRenderKeys(EnvRegistry& registry);

}  // namespace bvhlab
