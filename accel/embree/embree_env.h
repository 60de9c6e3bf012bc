// The env keys of the `embree` accelerator and the config they fill: each key declared once here
// and bound once (embreeKeys) to what it sets; the binding registers it, lists it as a key the
// accelerator reads and reads it.
#pragma once

#include "framework/config/common_keys.h"
#include "framework/config/key_bindings.h"

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

enum class EmbreeQuality { Low, Medium, High };

struct EmbreeConfig {
    EmbreeQuality quality = EmbreeQuality::Medium;
    bool robust = false;
    int threads = 0;  // as passed to rtcNewDevice: 0 = all hardware threads

    // Embree::quality, Embree::robust and Embree::threads (0 = SetRayTracing::threads).
    static EmbreeConfig fromEnv(const Env& env);
};

const KeyBindings<EmbreeConfig>& embreeKeys();

}  // namespace bvhlab
