// The env keys of the `embree` accelerator and the config they fill: each key declared once here
// and bound once (embree_env.cpp) to what it sets; the binding declares it to the registrar and
// reads it.
#pragma once

#include "framework/config/common_keys.h"
#include "framework/config/env.h"
#include "framework/config/key_bindings.h"

#include <vector>

namespace bvhlab {

namespace keys::Embree {
inline constexpr std::string_view kQualities[] = {"low", "medium", "high", "refit"};
inline constexpr ChoiceKey quality{
    "Embree::quality", "medium", kQualities,
    "Embree build quality: low (two-level, fastest build), medium (default), high (spatial splits), refit (a dynamic "
    "two-level scene, each geometry's tree built to be refitted by an update: RTC_BUILD_QUALITY_REFIT; the others "
    "have no update)"};
inline constexpr BoolKey robust{
    "Embree::robust", "false",
    "RTC_SCENE_FLAG_ROBUST: robust traversal, no optimisations that reduce arithmetic accuracy"};
inline constexpr IntKey threads{
    "Embree::threads", "0", 0, 1024,
    "Embree build threads; 0 = as SetRayTracing::threads. Process-wide: limits TBB while the device lives"};
inline constexpr std::string_view kIsas[] = {"auto", "sse2", "sse4.2", "avx", "avx2", "avx512"};
inline constexpr ChoiceKey isa{
    "Embree::isa", "auto", kIsas,
    "the widest SIMD kernels Embree may use (its device's max_isa): auto = the best this CPU runs; above the "
    "CPU's best, that best. avx2 beside BVH::isa=avx2 compares kernels of one vector width (bvhlab bench --isa-pairs)"};
}  // namespace keys::Embree

enum class EmbreeQuality { Low, Medium, High, Refit };

struct EmbreeConfig {
    EmbreeQuality quality = EmbreeQuality::Medium;
    bool robust = false;
    int threads = 0;     // as passed to rtcNewDevice: 0 = all hardware threads
    std::string maxIsa;  // as passed to rtcNewDevice's max_isa: empty = no limit (Embree::isa=auto)

    // Embree::quality, Embree::robust, Embree::threads (0 = SetRayTracing::threads) and Embree::isa,
    // as a structure reads its keys (<bvhlab/settings.h>).
    static EmbreeConfig from(const PluginSettings& keys);
    static EmbreeConfig fromEnv(const Env& env);
};

std::vector<EnvKey> embreeKeyDeclarations();

}  // namespace bvhlab
