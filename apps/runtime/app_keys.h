// The env keys the program itself reads: where the scene comes from (scene_loading.cpp), what a
// render writes (render and batch) and the batch's thread count.
#pragma once

#include "framework/config/env.h"

namespace bvhlab {

namespace keys::Scene {
inline constexpr PathKey dir{"Scene::dir", "../shared/scenes", "folder that relative Scene::file names are read from"};
inline constexpr TextKey file{"Scene::file", "",
                              "scene file (.obj .ply .off .nff .aff, optionally .gz), relative to Scene::dir; empty = "
                              "the embedded default scene"};
inline constexpr IntKey frame{
    "Scene::frame", "0", 0, (1 << 30) - 1,
    "animated scenes (.aff): the frame to load, 0 = the animation's first; its geometry, camera and lights at that "
    "frame's time. A frame past the last is an error; a still scene ignores the key (with a warning unless 0)"};
inline constexpr PathKey cacheDir{
    "Scene::cacheDir", "$XDG_CACHE_HOME/bvhlab/scenes",
    "binary cache of parsed scenes, keyed by the source file's bytes (bvhlab batch); empty = no cache"};
}  // namespace keys::Scene

namespace keys::Output {
inline constexpr BoolKey exr{"Output::exr", "true", "write PATH.exr (RGB, depth, primitive, normal, N_TR, N_IT)"};
inline constexpr BoolKey png{"Output::png", "true", "write PATH.png (tone-mapped RGB)"};
inline constexpr BoolKey heatmap{"Output::heatmap", "false",
                                 "also write PATH.heatmap.png: traversal steps per pixel, with a colour bar"};
inline constexpr FloatKey heatmapScale{
    "Output::heatmapScale", "0", 0, 1e30,
    "heat map full scale in traversal steps per pixel, fixed so heat maps compare; 0 = per image (its 99th "
    "percentile; bvhlab batch: one per scene)"};
}  // namespace keys::Output

namespace keys::Batch {
inline constexpr IntKey threads{
    "Batch::threads", "1", 0, 1024,
    "bvhlab batch: render and Embree build threads, replacing SetRayTracing::threads; 1 = the report's setting, 0 = "
    "all hardware threads"};
inline constexpr BoolKey animate{
    "Batch::animate", "true",
    "bvhlab batch: an animated scene (.aff) runs as an animation, Animate::frames under Animate::policy, measured "
    "as bvhlab animate measures a contender; false: rendered as a still scene at Scene::frame"};
}  // namespace keys::Batch

namespace keys::Spd {
inline constexpr IntKey maxDepth{"Spd::maxDepth", "5", 1, 64,
                                 "bvhlab spd: ray tree depth, the eye ray being depth 1 (the SPD rules: 5)"};
inline constexpr TextKey twoSidedScenes{
    "Spd::twoSidedScenes", "teapot",
    "bvhlab spd: comma-separated scenes whose opaque primitives are seen from both sides (the SPD rules: the "
    "teapot); the others' are one-sided"};
inline constexpr PathKey reference{
    "Spd::reference", "../shared/reference/spd",
    "bvhlab spd: folder of Havran's havran_stats_grids.txt and havran_stats_octrees.txt"};
}  // namespace keys::Spd

namespace keys::Animate {
inline constexpr std::string_view kPolicies[] = {"rebuild", "refit", "adaptive", "twolevel"};
inline constexpr ChoiceKey policy{
    "Animate::policy", "adaptive", kPolicies,
    "how a structure follows an animation (bvhlab animate, docs/animation.md; per structure as --accel "
    "NAME:Animate::policy=P): rebuild every frame; refit (the "
    "structure's update: BVH::update, Embree::quality=refit); adaptive (refit, and rebuild when the SAH has grown "
    "past Animate::sahGrowth or every Animate::rebuildEvery frames); twolevel (a structure per rigid part under a "
    "top level)"};
inline constexpr FloatKey sahGrowth{
    "Animate::sahGrowth", "1.3", 1, 1e9,
    "adaptive: rebuild once the refitted tree's SAH exceeds this factor of the SAH of its last build"};
inline constexpr IntKey rebuildEvery{"Animate::rebuildEvery", "0", 0, 1000000,
                                     "adaptive: rebuild at least every this many frames; 0 = only when the SAH grew"};
inline constexpr TextKey frames{
    "Animate::frames", "all",
    "the frames an animation measures (bvhlab animate without --frames, bvhlab batch): all, or FIRST:END[:STRIDE], END "
    "excluded"};
}  // namespace keys::Animate

// Keys that change no figure of any run: what is written (Output::*) and where parsed scenes
// are cached. Batch and tradeoff leave them out of what a stored result must match.
inline bool changesNoFigure(std::string_view name) {
    return name.starts_with("Output::") || name == keys::Scene::cacheDir.name();
}

}  // namespace bvhlab
