// The env keys of the `embree` accelerator, read by EmbreeConfig::fromEnv.
#pragma once

#include "framework/config/common_keys.h"

namespace bvhlab {

namespace keys::Embree {
inline constexpr std::string_view kQualities[] = {"low", "medium", "high"};
inline constexpr ChoiceKey quality{
    "Embree::quality", "medium", kQualities,
    "Embree build quality: low (two-level, fastest build), medium (default), high (spatial splits)"};
inline constexpr BoolKey robust{"Embree::robust", "false",
                                "RTC_SCENE_FLAG_ROBUST: robust traversal, no optimisations that reduce arithmetic accuracy"};
inline constexpr IntKey threads{
    "Embree::threads", "0", 0, 1024,
    "Embree build threads; 0 = as SetRayTracing::threads. Process-wide: limits TBB while the device lives"};
}  // namespace keys::Embree

void registerEmbreeKeys(EnvRegistry& registry);

}  // namespace bvhlab
