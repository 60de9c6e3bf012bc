#include "framework/config/env_keys.h"

namespace bvhlab {

void registerFrameworkKeys(EnvRegistry& r, const std::vector<std::string>& acceleratorNames) {
    using T = EnvType;
    r.add({"ASDS::type", T::Choice, "sahbvh", "acceleration structure to build and trace with", 0, 0, acceleratorNames});

    r.add({"SetRayTracing::cntSamples", T::Int, "1", "samples per pixel; above 1 they are stratified jittered", 1, 65536, {}});
    r.add({"SetRayTracing::depthLimit", T::Int, "1", "path length: 1 = primary rays only, more allows mirror bounces", 1, 64, {}});
    r.add({"SetRayTracing::shadows", T::Bool, "true", "cast a shadow ray per light and shading point", 0, 0, {}});
    r.add({"SetRayTracing::threads", T::Int, "0", "render threads (and Embree's); 0 = all hardware threads, 1 = the report's setting", 0, 1024, {}});

    r.add({"Scene::dir", T::Path, "../shared/scenes", "folder that relative Scene::file names are read from", 0, 0, {}});
    r.add({"Scene::file", T::String, "", "scene file (.obj .ply .off .nff, optionally .gz), relative to Scene::dir; empty = the embedded default scene", 0, 0, {}});
    r.add({"Scene::cacheDir", T::Path, ".cache/scenes", "binary cache of parsed scenes, keyed by the source file's bytes (bvhlab batch); empty = no cache", 0, 0, {}});
    r.add({"Scene::background", T::Vec3, "", "background colour on a miss; empty = the scene's, else dark blue", 0, 0, {}});

    r.add({"Camera::from", T::Vec3, "", "eye position; empty = the scene's camera, else a view framing the scene", 0, 0, {}});
    r.add({"Camera::at", T::Vec3, "", "point looked at; empty = as Camera::from", 0, 0, {}});
    r.add({"Camera::up", T::Vec3, "", "up direction; empty = the scene's, else +y", 0, 0, {}});
    r.add({"Camera::fovy", T::Float, "0", "vertical field of view in degrees; 0 = the scene's, else 45", 0, 179, {}});
    r.add({"Camera::width", T::Int, "0", "image width in pixels; 0 = the scene's, else 512", 0, 16384, {}});
    r.add({"Camera::height", T::Int, "0", "image height in pixels; 0 = the scene's, else 512", 0, 16384, {}});

    r.add({"Lights::positions", T::Vec3List, "", "point lights 'x y z, x y z'; empty = the scene's, else one above the camera", 0, 0, {}});
    r.add({"Lights::intensity", T::Float, "1", "irradiance each env light gives at the scene centre (falls off with distance squared)", 0, 1e30, {}});

    r.add({"Render::ambient", T::Float, "0.05", "ambient term so that shadowed surfaces stay visible", 0, 1, {}});

    r.add({"Batch::threads", T::Int, "1", "bvhlab batch: render and Embree build threads, replacing SetRayTracing::threads; 1 = the report's setting, 0 = all hardware threads", 0, 1024, {}});

    r.add({"Output::exr", T::Bool, "true", "write PATH.exr (RGB, depth, primitive, normal, N_TR, N_IT)", 0, 0, {}});
    r.add({"Output::png", T::Bool, "true", "write PATH.png (tone-mapped RGB)", 0, 0, {}});
    r.add({"Output::heatmap", T::Bool, "false", "also write PATH.heatmap.png: traversal steps per pixel, with a colour bar", 0, 0, {}});
    r.add({"Output::heatmapScale", T::Float, "0", "heat map full scale in traversal steps per pixel, fixed so heat maps compare; 0 = per image (its 99th percentile; bvhlab batch: one per scene)", 0, 1e30, {}});
}

}  // namespace bvhlab
